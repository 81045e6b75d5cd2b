/* summary.h: the -summary JSON written at the end of every run (success or failure), and the
 * state hash that proves bitwise determinism.
 *
 * The JSON is one object with the standard keys (in this order):
 *   version, status, reason, steps, time, nodes, elements, joints, joints_broken, contact_pairs,
 *   energy {kinetic, strain, external_work, damping, joint_dissipated, contact, friction},
 *   wall_s, element_steps_per_s, threads, state_hash
 * followed by extra keys that modules register with summary_add_number / summary_add_raw.
 * A non-finite number is written as null; it turns status "ok" into "numerical_failure".
 */
#ifndef YF_SUMMARY_H
#define YF_SUMMARY_H
#include <stdint.h>
#include "sim.h"

/* Write the summary of s to path atomically (path.tmp, fsync, rename).  status_code is a
 * YF_EXIT_* code, reason the message ("" when none; NULL: yf_last_message()).  Returns the
 * status code actually written (YF_EXIT_NUMERIC when an "ok" summary held a non-finite number),
 * or -1 when the file could not be written (errno set).  Never exits: it runs from the error
 * cleanup path too. */
int summary_write(const YfSim *s, const char *path, int status_code, const char *reason);

/* Counters owned by the physics modules (joint.c, contact.c); 0 until they set them. */
void summary_set_counts(long joints, long joints_broken, long contact_pairs);

/* Extra top-level keys, emitted after the standard ones in the order first added; adding a key
 * again replaces its value.  Keys must not be standard keys.  json_text is emitted verbatim
 * (it must be valid JSON: a number, string, array or object). */
void summary_add_number(const char *key, double v);
void summary_add_raw(const char *key, const char *json_text);
void summary_clear_extras(void);

/* FNV-1a 64 over the raw bytes of x, y, vx, vy of every node (in that order per node, nodes in
 * index order).  Two runs with equal hashes have bitwise-identical positions and velocities
 * (a single flipped bit changes the hash), so comparing hashes across thread counts or
 * machines proves bitwise determinism; it says nothing about results being close. */
uint64_t sim_state_hash(const YfSim *s);

/* JSON string literal of s (with quotes) into out (cap bytes, truncated safely).  Escapes
 * quotes, backslashes and control characters; invalid UTF-8 bytes become U+FFFD. */
void summary_json_string(char *out, size_t cap, const char *s);

#endif
