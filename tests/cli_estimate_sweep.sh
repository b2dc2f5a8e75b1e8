#!/usr/bin/env bash
# `sweep --run scan` reports each scan's error estimate as `tiptap scan` does (issue 30):
# energy_balance is the energy-balance check (the column named error_estimate before),
# error_estimate_height_nm and error_estimate_phase_deg the largest of the scan's own
# estimate, equal to what `tiptap scan` prints for the same scene, and larger at the
# looser tolerance.
# usage: cli_estimate_sweep.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

cat "$src/tests/estimate-particles.ini" - >"$tmp/s.ini" <<'INI'
[scan]
size = 200 nm
pixels = 8
lines = 8
line_rate = 50 Hz
channels = height, error, phase
INI

"$tiptap" sweep "$tmp/s.ini" --vary "solver.tolerance=1e-6,1e-8" --run scan -o "$tmp/w.csv" -q ||
  { bad "sweep failed"; exit 1; }
for tol in 1e-6 1e-8; do
  "$tiptap" scan "$tmp/s.ini" --set solver.tolerance=$tol -o "$tmp/s$tol" 2>"$tmp/s$tol.err" >/dev/null ||
    bad "scan at $tol failed"
done

python3 - "$tmp" <<'PY' || fail=1
import csv, sys
tmp = sys.argv[1]
rows = [r for r in csv.DictReader(open(tmp + '/w.csv')) if r['material'] == 'all']
status = 0
def check(name, cond, detail):
    global status
    print(('ok   ' if cond else 'FAIL ') + name + ': ' + detail)
    status |= not cond
check('columns', 'error_estimate' not in rows[0] and 'energy_balance' in rows[0] and
      'error_estimate_height_nm' in rows[0] and 'error_estimate_phase_deg' in rows[0],
      ','.join(rows[0].keys()))
est = []
for r, tol in zip(rows, ('1e-6', '1e-8')):
    err = open('%s/s%s.err' % (tmp, tol)).read().splitlines()
    def scan_max(key):
        line = next(l for l in err if l.startswith(key + ' = '))
        return float(line.split('max ')[1].rstrip(')'))
    h, p = float(r['error_estimate_height_nm']), float(r['error_estimate_phase_deg'])
    sh, sp = scan_max('error_estimate_height_m') * 1e9, scan_max('error_estimate_phase_deg')
    check('tolerance %s: as tiptap scan reports' % tol,
          abs(h - sh) <= 0.06 * sh and abs(p - sp) <= 0.06 * sp,
          'sweep %.3g nm %.3g deg, scan %.3g nm %.3g deg; energy_balance %s' % (h, p, sh, sp, r['energy_balance']))
    est.append(h)
check('looser tolerance, larger estimate', est[0] > est[1], '%.3g nm at 1e-6, %.3g nm at 1e-8' % tuple(est))
sys.exit(status)
PY
exit $fail
