#!/usr/bin/env bash
# Builds Prahl's iad (https://github.com/scottprahl/iad, MIT licence) from a checkout in IAD_DIR as
# iad_hp: iad 4 unchanged except that its result rows print "%.10g" instead of "%6.4f" (4 decimals
# are too few to compare mu_a and mu_s' at 0.1 %). The checkout's generated C sources are used;
# nothing of iad is copied into this repository.
# Usage: tools/validation/iad_precision.sh IAD_DIR      -> IAD_DIR/src/iad_hp and IAD_DIR/src/iad
set -euo pipefail
dir="${1:?usage: iad_precision.sh IAD_DIR (a checkout of scottprahl/iad)}"
cd "$dir/src"
flags="-O3 -fno-common -DNDEBUG -fPIC -fsigned-char"
make iad CFLAGS="$flags" >/dev/null
cp iad iad_orig
/usr/bin/python3 - <<'PY'
s = open('iad_main.c').read()
a = s.index('void print_optical_property_result')
b = s.index('fflush(fp);', a)
seg = s[a:b]
k = seg.rindex('else {')
tail = seg[k:].replace('"%6.4f\\t%6.4f\\t"', '"%.10g\\t%.10g\\t"').replace('"%6.4f\\t"', '"%.10g\\t"')
tail = tail.replace('"%6.1f\\t"', '"%.10g\\t"').replace('if (mu_a >= 200)', 'if (0)').replace('if (mu_sp >= 1000)', 'if (0)')
open('iad_main_hp.c', 'w').write(s[:a] + seg[:k] + tail + s[b:])
PY
objects=$(ls *.o | grep -v -e '^iad_main' -e '^ad_main' -e test -e mc_lost_main | tr '\n' ' ')
cc $flags -c -o iad_main_hp.o iad_main_hp.c
cc -o iad_hp $objects iad_main_hp.o -lm
mv iad_orig iad
echo "built $dir/src/iad_hp (and the unchanged $dir/src/iad)"
