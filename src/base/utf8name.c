/* utf8name.c: one UTF-8 character decoded and, when it stands in for ASCII, named (see utf8name.h). */
#include <stdio.h>
#include <string.h>
#include "utf8name.h"

int yf_utf8_decode(const char *s, unsigned *cp) {
  const unsigned char *u = (const unsigned char *)s;
  unsigned c = u[0];
  *cp = c;
  if (c < 0x80) return 1;
  /* the lead byte gives the length; 0xC0, 0xC1 and 0xF5.. can only start an overlong or too
   * large sequence, which the checks below refuse */
  int len = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
  if (!len) return 0;
  unsigned v = c & (0x7Fu >> len);
  for (int k = 1; k < len; k++) {
    if ((u[k] & 0xC0) != 0x80) return 0; /* also stops at the terminating NUL */
    v = v << 6 | (u[k] & 0x3F);
  }
  static const unsigned least[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (v < least[len] || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) return 0;
  *cp = v;
  return len;
}

int yf_lookalike(unsigned cp, YfLookalike *l) {
  /* code points lo..hi, checked in order (a single one before the range that holds it) */
  static const struct {
    unsigned lo, hi;
    const char *name, *ascii;
  } table[] = {
      {0x00A0, 0x00A0, "a no-break space", "a space"},
      {0x202F, 0x202F, "a narrow no-break space", "a space"},
      {0x2009, 0x2009, "a thin space", "a space"},
      {0x2000, 0x200A, "a Unicode space", "a space"},
      {0x3000, 0x3000, "an ideographic space", "a space"},
      {0x200B, 0x200B, "a zero-width space", ""},
      {0xFEFF, 0xFEFF, "a zero-width no-break space", ""},
      {0x2212, 0x2212, "a minus sign", "-"},
      {0x2010, 0x2015, "a dash", "-"},
      {0x2018, 0x2019, "a typographic quote", "' or \""},
      {0x201C, 0x201D, "a typographic quote", "\" or '"},
      {0x00D7, 0x00D7, "a multiplication sign", "*"},
      {0x22C5, 0x22C5, "a dot operator", "*"},
      {0x00B7, 0x00B7, "a middle dot", "*"},
      {0x00F7, 0x00F7, "a division sign", "/"},
      {0x00B2, 0x00B2, "a superscript", "^2"},
      {0x00B3, 0x00B3, "a superscript", "^3"},
      {0x03C0, 0x03C0, "pi", "pi"},
      /* full-width forms U+FF01..U+FF5E are ASCII '!'..'~' shifted by 0xFEE0 */
      {0xFF10, 0xFF19, "a full-width digit", NULL},
      {0xFF01, 0xFF5E, "a full-width character", NULL},
  };
  for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
    if (cp >= table[i].lo && cp <= table[i].hi) {
      l->name = table[i].name;
      if (table[i].ascii)
        snprintf(l->ascii, sizeof l->ascii, "%s", table[i].ascii);
      else
        snprintf(l->ascii, sizeof l->ascii, "%c", (char)(cp - 0xFEE0));
      return 1;
    }
  return 0;
}
