/* cmd_contact.c: the `contact` deck command (a row of commands.def): checks the groups it names
 * and sets contact rules and options (contact_add_rule, contact_set_option, contact.h).
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "contact.h"
#include "deck.h"

/* A pair or self rule: the same pair again is no new rule. */
static void add_rule(YfSim *s, const YfArgs *a, int g1, int g2) {
  if (contact_add_rule(s, g1, g2, &a->loc) < 0)
    arg_error(a, 0, "at most %d contact rules (pair/self lines)", YF_CONTACT_MAX_RULES);
}

static void group_names(const YfModel *m, char *buf, size_t cap) {
  size_t k = 0;
  buf[0] = 0;
  for (int g = 0; g < m->ngroup && k + 2 < cap; g++) {
    int w = snprintf(buf + k, cap - k, "%s%s", g ? " " : "", m->group[g].name);
    if (w < 0) break;
    k += (size_t)w;
  }
  if (!buf[0]) snprintf(buf, cap, "none");
}

/* Group word i of a contact command: must exist and hold triangles whose materials have pen_n (a pen_n
 * of 0 written out is meant: the couples exist and carry no force, as Y2D's of a property of D1PEPE 0). */
static int rule_group(YfSim *s, const YfArgs *a, int i) {
  YfModel *m = &s->model;
  const char *name = arg_word(a, i, "group");
  int g = model_group(m, name, 0);
  if (g < 0) {
    char have[1024];
    group_names(m, have, sizeof have);
    arg_error(a, i, "no such group or body (defined: %s)", have);
  }
  uint64_t bit = (uint64_t)1 << g;
  int ntri = 0;
  for (int t = 0; t < m->tri.n; t++) {
    if (!(m->tri.gmask[t] & bit)) continue;
    ntri++;
    const YfMaterial *mt = &m->mat[m->tri.mat[t]];
    if (!(mt->pen_n > 0) && !mt->pen_n_given)
      arg_error(a, i, "material '%s' of its triangles has no normal contact penalty: add 'pen_n P' [Pa] "
                "(typically 1-10 x E) to its material command", mt->name);
  }
  if (!ntri) arg_error(a, i, "group has no triangles (contact acts between triangles)");
  return g;
}

/* contact pair G1 G2 | contact self G | contact off |
 * contact KEY VALUE [KEY VALUE ...] with KEY buffer D|auto, joined keep|skip,
 *                                         surface boundary|all, search travel|every, shared skip|keep */
void cmd_contact(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, -1);
  static const char *const words[] = {"pair", "self", "off", "buffer", "joined", "surface", "search", "shared", NULL};
  int k = arg_choice(a, 0, "contact keyword", words);
  if (k == 0) {
    arg_count(a, 3, 3);
    int g1 = rule_group(s, a, 1), g2 = rule_group(s, a, 2);
    add_rule(s, a, g1, g2);
    return;
  }
  if (k == 1) {
    arg_count(a, 2, 2);
    int g = rule_group(s, a, 1);
    add_rule(s, a, g, g);
    return;
  }
  if (k == 2) {
    arg_count(a, 1, 1);
    contact_off(s);
    return;
  }
  for (int i = 0; i < a->n; i += 2) {
    int key = arg_choice(a, i, "contact option", words + 3) + 3;
    if (i + 1 >= a->n) arg_error(a, i, "option needs a value");
    if (key == 3) {
      contact_set_option(s, YF_CONTACT_BUFFER,
                         strcmp(a->w[i + 1], "auto") ? arg_nonneg(a, i + 1, "buffer [m] (or auto)") : -1.0);
    } else if (key == 4) {
      static const char *const v[] = {"keep", "skip", NULL};
      contact_set_option(s, YF_CONTACT_JOINED, arg_choice(a, i + 1, "joined", v));
    } else if (key == 5) {
      static const char *const v[] = {"boundary", "all", NULL};
      contact_set_option(s, YF_CONTACT_SURFACE, arg_choice(a, i + 1, "surface", v));
    } else if (key == 6) {
      static const char *const v[] = {"travel", "every", NULL};
      contact_set_option(s, YF_CONTACT_SEARCH, arg_choice(a, i + 1, "search", v));
    } else { /* couples of triangles that share a node: skipped (default), or kept as Y2D keeps them */
      static const char *const v[] = {"skip", "keep", NULL};
      contact_set_keep_shared(s, arg_choice(a, i + 1, "shared", v));
    }
  }
}
