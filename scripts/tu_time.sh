#!/bin/sh
# Compiler/linker launcher for scripts/ci_timing.sh: runs the command under
# /usr/bin/time and appends "user sys wall output" to $TU_TIME_LOG, so a build
# says which translation units and links its CPU time goes to.
out=-
prev=
for a in "$@"; do
  [ "$prev" = "-o" ] && out=$a
  prev=$a
done
if [ -z "${TU_TIME_LOG:-}" ]; then exec "$@"; fi
exec /usr/bin/time -a -o "$TU_TIME_LOG" -f "%U %S %e ${PWD#${TU_TIME_ROOT:-}/}/$out" "$@"
