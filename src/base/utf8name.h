/* utf8name.h: one character of UTF-8 text, decoded and named, for the messages that quote what a
 * user typed.  Decks copied from a word processor, a PDF or a web page hold look-alikes of ASCII
 * characters (a minus sign U+2212, a no-break space, typographic quotes, full-width digits) that
 * a quoted token hides: "'200 ' is not a number".  Every reader that quotes a token names them
 * from the one table here, so a look-alike one reader names the others name too; each reader
 * words its own advice around the name (the deck's expressions, the Y2D reader). */
#ifndef YF_UTF8NAME_H
#define YF_UTF8NAME_H

/* The character that starts at s: its length in bytes (1 for ASCII, 2 to 4 for a well-formed
 * UTF-8 sequence) and *cp its code point; 0 when s starts no well-formed UTF-8 character (a
 * stray continuation byte, a Latin-1 byte, a truncated or overlong sequence, a surrogate, a code
 * beyond U+10FFFF), *cp then the byte itself.  s must not be at its terminating NUL. */
int yf_utf8_decode(const char *s, unsigned *cp);

/* A known look-alike of ASCII text: what it is and what to type instead. */
typedef struct {
  const char *name;  /* "a minus sign", "a no-break space", "a full-width digit" */
  char ascii[12];    /* the ASCII it stands for: "-", "a space", "\" or '", "3"; "" when nothing
                      * should be typed (a zero-width space: delete it) */
} YfLookalike;

/* Returns 1 and fills *l when code point cp is a known look-alike, 0 when it is not. */
int yf_lookalike(unsigned cp, YfLookalike *l);

#endif
