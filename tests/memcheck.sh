#!/bin/bash
# One Catch test case run under valgrind's memcheck: any invalid read or
# write, or use of uninitialised memory, fails it (exit 99). The self-contact
# read past the end of its vertex areas for every edge-edge pair numbered
# beyond the vertices, without a wrong value and without a crash, until an
# outside check's valgrind run found it (and 2 of 8 resumed optimisations
# died of it). Exit 77 (skipped, with the reason) when valgrind is missing.
#   memcheck.sh TEST_PROGRAM "test case name"
set -u
if ! command -v valgrind >/dev/null; then
  echo "skipped: valgrind is not installed (apt-get install valgrind; scripts/setup.sh installs it)"
  exit 77
fi
exec valgrind --error-exitcode=99 --errors-for-leak-kinds=none -q "$1" "$2" -w NoTests
