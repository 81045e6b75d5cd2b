/* cmd_jointprop.c: the `jointprop` deck command (a row of commands.def): reads the words (and a
 * softening table file) into a YfJointProp and adds a joint set (joints_add_set, joint.h).
 */
#include <math.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "joint.h"

/* Two-column table file (opening, stress; '#' comments) for law table: stresses are divided by
 * the first one, so the file may hold Pa or already normalised values; openings in any unit. */
static void read_table(const YfArgs *a, int i, YfJointProp *p) {
  char *path = deck_resolve_path(a, a->w[i]);
  FILE *fp = yf_open_input(path, "r");
  if (!fp) yf_io_error(&a->loc, "jointprop: cannot open softening table '%s': %s", path, strerror(errno));
  double w[YF_JOINT_TAB_MAX], sv[YF_JOINT_TAB_MAX];
  int n = 0, line = 0;
  char *buf = NULL; /* whole lines, however long: a long comment must not split a line in two */
  size_t cap = 0;
  while (yf_getline(&buf, &cap, fp) >= 0) {
    line++;
    if (line == 1) yf_skip_bom(buf);
    char *h = strchr(buf, '#');
    if (h) *h = 0;
    double u, v;
    char extra[8];
    int k = sscanf(buf, "%lf %lf %7s", &u, &v, extra);
    if (k == EOF) continue; /* a blank (or comment) line; a line of words is an error below */
    if (k != 2) {
      fclose(fp);
      free(buf);
      yf_deck_error(&a->loc, "%s:%d: expected two numbers 'opening stress' per line", path, line);
    }
    if (n == YF_JOINT_TAB_MAX) {
      fclose(fp);
      free(buf);
      yf_deck_error(&a->loc, "%s: more than %d points in the softening table", path, YF_JOINT_TAB_MAX);
    }
    w[n] = u;
    sv[n++] = v;
  }
  free(buf);
  fclose(fp);
  if (n < 2 || !(sv[0] > 0)) yf_deck_error(&a->loc, "%s: the softening table needs >= 2 points starting at a stress > 0", path);
  for (int k = n - 1; k >= 0; k--) sv[k] /= sv[0];
  char why[256];
  if (!joint_prop_set_table(p, n, w, sv, why, sizeof why)) yf_deck_error(&a->loc, "%s: %s", path, why);
  free(path);
}

/* jointprop NAME ft FT fs FS gf GF pen P [law ...] [cohesion C friction MU] [damage ...]
 *           [floor y2d|none] [weibull M | normal CV] [seed S] [tangent exact|y2d] */
void cmd_jointprop(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, -1);
  const char *name = arg_name(a, 0, "name");
  if (joints_find_set(s, name) >= 0) arg_error(a, 0, "jointprop already defined (each name once)");
  YfJointProp p;
  joint_prop_default(&p);
  p.irreversible = 1; /* native decks: damage never decreases (read_y2d keeps Y2D's reversible law) */
  p.hreg = 0.0;       /* native decks: no absolute length in the law (units must not matter) */
  int given[4] = {0, 0, 0, 0}, het = YF_HET_NONE;
  double het_par = 0;
  unsigned long seed = 1;
  int fric_at = 0; /* word of 'friction', to name it when there is no cohesion */
  static const char *const keys[] = {"ft", "fs", "gf", "pen", "law", "cohesion", "friction", "damage", "floor",
                                     "weibull", "normal", "seed", "tangent", NULL};
  static const char *const laws[] = {"munjiza", "munjiza_gf", "linear", "bilinear", "table", NULL};
  static const char *const dmg[] = {"reversible", "irreversible", NULL};
  static const char *const floors[] = {"y2d", "none", NULL};
  p.coh = 0;
  for (int i = 1; i < a->n;) {
    int k = arg_choice(a, i, "keyword", keys);
    if (i + 1 >= a->n) arg_error(a, i, "keyword needs a value");
    switch (k) {
    case 0: p.ft = arg_pos(a, i + 1, "ft"); given[0] = 1; break;
    case 1: p.fs = arg_pos(a, i + 1, "fs"); given[1] = 1; break;
    case 2: p.gf = arg_pos(a, i + 1, "gf"); given[2] = 1; break;
    case 3: p.pen = arg_pos(a, i + 1, "pen"); given[3] = 1; break;
    case 4: {
      int l = arg_choice(a, i + 1, "law", laws);
      p.law = l;
      if (l == YF_SOFT_TABLE) {
        if (i + 2 >= a->n) arg_error(a, i + 1, "law table needs a FILE (two columns: opening, stress)");
        read_table(a, i + 2, &p);
        i += 3;
        continue;
      }
      if (l == YF_SOFT_BILINEAR && i + 2 < a->n && !strcmp(a->w[i + 2], "kink")) {
        p.bl_z = arg_num(a, i + 3, "kink opening fraction");
        p.bl_s = arg_num(a, i + 4, "kink stress fraction");
        i += 5;
        continue;
      }
      break;
    }
    case 5: p.coh = arg_pos(a, i + 1, "cohesion"); break;
    case 6: p.phi = arg_nonneg(a, i + 1, "friction"); fric_at = i; break;
    case 7: p.irreversible = arg_choice(a, i + 1, "damage", dmg); break;
    case 8: p.y2d_floor = arg_choice(a, i + 1, "floor", floors) == 0; break;
    case 9:
    case 10:
      if (het != YF_HET_NONE) arg_error(a, i, "give one of weibull M or normal CV");
      het = k == 9 ? YF_HET_WEIBULL : YF_HET_NORMAL;
      het_par = arg_pos(a, i + 1, k == 9 ? "Weibull modulus" : "coefficient of variation");
      /* the mean-1 scale is 1 / Gamma(1 + 1/M): beyond a double below M = 1/171 (GSL aborted) */
      if (k == 9 && het_par < 0.01)
        arg_error(a, i + 1, "a Weibull modulus below 0.01 spreads the strengths beyond what doubles hold (its mean-1 "
                  "scale 1/Gamma(1 + 1/M) underflows); concrete and rock have 5-20");
      /* the normal draw is redrawn until > 0 (joints.c): a truncated normal, whose mean
       * 1 + CV phi(1/CV) / Phi(1/CV) leaves 1 by more than 1 % above CV 0.42 */
      if (k == 10) {
        double z = 1.0 / het_par, mean = 1.0 + het_par * exp(-0.5 * z * z) / sqrt(2.0 * M_PI) / (0.5 * erfc(-z / sqrt(2.0)));
        if (mean > 1.01)
          yf_warn(&a->loc, "jointprop %s: normal %g: factors at or below 0 are drawn again, so their mean is %.3g, not "
                  "1 (%.2g %% of draws fall there); for a scatter this wide use 'weibull M'", name, het_par, mean,
                  100.0 * 0.5 * erfc(z / sqrt(2.0)));
      }
      break;
    case 11: seed = (unsigned long)arg_int(a, i + 1, "seed", 0, 4294967295L); break;
    case 12: {
      /* y2d: Y2D's unit tangent e/(h + 1e-10 m) (an absolute length: the scene must be in m) */
      static const char *const tang[] = {"exact", "y2d", NULL};
      p.hreg = arg_choice(a, i + 1, "tangent", tang) ? 1e-10 : 0.0;
      break;
    }
    }
    i += 2;
  }
  if (!given[0]) arg_error(a, 0, "missing 'ft FT' (tensile strength, Pa)");
  if (!given[2]) arg_error(a, 0, "missing 'gf GF' (fracture energy, J/m^2)");
  if (!given[3]) arg_error(a, 0, "missing 'pen P' (joint penalty, Pa; about 10-100 x E)");
  if (!given[1] && !(p.coh > 0)) arg_error(a, 0, "missing 'fs FS' (shear strength, Pa) or 'cohesion C'");
  /* Mohr-Coulomb is on only with a cohesion (ALGORITHMS 3.5): a friction alone was ignored in silence */
  if (p.phi > 0 && !(p.coh > 0))
    arg_error(a, fric_at, "friction acts only with 'cohesion C' (Mohr-Coulomb f_s = C - sigma MU, C > 0 Pa); "
              "add cohesion C or drop friction");
  if (!given[1]) p.fs = 0;
  joints_add_set(s, name, &p, het, het_par, seed, &a->loc);
}
