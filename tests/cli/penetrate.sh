#!/usr/bin/env bash
# `spall penetrate`: the check value, --help for each mode, CSV outputs, and
# bad input -> one line on stderr, exit 2.  Usage: penetrate.sh SPALL SRC
set -u
spall="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0
pass=0
ok() { pass=$((pass+1)); }
ko() { echo "FAIL $*"; fail=$((fail+1)); }

bad() { # name expected-substring args...
    local name="$1" expect="$2"
    shift 2
    "$spall" penetrate "$@" >stdout.txt 2>stderr.txt
    local rc=$? lines
    lines=$(wc -l < stderr.txt)
    if [ $rc -ne 2 ]; then ko "$name: exit $rc, expected 2"; cat stderr.txt; return; fi
    if [ "$lines" -ne 1 ]; then ko "$name: $lines lines on stderr"; cat stderr.txt; return; fi
    if ! grep -q -- "$expect" stderr.txt; then ko "$name: message lacks '$expect'"; cat stderr.txt; return; fi
    ok
}

gel="--diameter 7.38e-6 --v0 1290 --projectile silica --target gelatin --Cd 0.375 --R 21e6"
# check value: 65.78 um (69.47 with the nose)
out=$("$spall" penetrate poncelet $gel) || ko "poncelet run"
echo "$out" | grep -q "P_max            6.57794e-05" && ok || { ko "P_max line"; echo "$out"; }
echo "$out" | grep -q "P_max + d/2      6.94694e-05" && ok || ko "nose line"
# --radius is the decks' impactor radius: the same run as --diameter 2r
rad=$("$spall" penetrate poncelet --radius 3.69e-6 --v0 1290 --projectile silica --target gelatin \
      --Cd 0.375 --R 21e6) || ko "radius run"
[ "$rad" = "$out" ] && ok || { ko "--radius 3.69e-6 differs from --diameter 7.38e-6"; echo "$rad"; }
# trajectory CSV: header and 201 rows, last P = P_max
"$spall" penetrate poncelet $gel --csv traj.csv >/dev/null || ko "csv run"
[ "$(grep -vc '^#' traj.csv)" -eq 202 ] && ok || ko "traj.csv rows"
# help for every mode, exit 0
for m in poncelet liu mcg fit sweep; do
    "$spall" penetrate $m --help >/dev/null 2>&1 && ok || ko "help $m"
done
"$spall" penetrate >/dev/null 2>&1; [ $? -eq 2 ] && ok || ko "no args"
# fit (a) on a self-made trajectory recovers C_d, R
"$spall" penetrate fit --model poncelet --trajectory traj.csv $gel --Cd 0.7 --R 9e6 --csv fit.csv > fit.txt 2>&1 || { ko "fit"; cat fit.txt; }
grep -Eq "^C_d +0\.375" fit.txt && ok || { ko "fit C_d"; cat fit.txt; }
[ -s fit.csv ] && ok || ko "fit.csv"
# fit (b) on the recorded MCG references recovers eta; --curve writes 5 x 200 rows
grep -v '^#' "$src/data/penetration/sebs_mcg_reference.csv" | cut -d, -f1,2,4 > pts_ok.csv
"$spall" penetrate fit --model mcg --points pts_ok.csv --projectile steel --target sebs \
    --curve curve.csv > fitb.txt 2>&1 || { ko "fit b"; cat fitb.txt; }
grep -Eq "^eta +0\.045 " fitb.txt && ok || { ko "fit b eta"; cat fitb.txt; }
[ "$(grep -vc '^#' curve.csv)" -eq 1001 ] && ok || ko "curve rows"
# sweep writes the table; MCG warns above Re = 1e5 but succeeds
"$spall" penetrate sweep --model mcg --projectile steel --target sebs --eta 4.5e-2 --R 25e6 \
    --diameter 10e-6,20e-6 --v0 100:900:100 --csv sweep.csv >/dev/null || ko "sweep"
[ "$(grep -vc '^#' sweep.csv)" -eq 19 ] && ok || ko "sweep rows"
# results are never replaced silently (as spall run): the same sweep again is
# refused before anything is written, and --overwrite replaces them
sum=$(cksum < sweep.csv)
swp="sweep --model mcg --projectile steel --target sebs --eta 4.5e-2 --R 25e6 --diameter 10e-6 --v0 100:900:100"
bad "sweep csv exists" "'sweep.csv' exists; give --overwrite" $swp --csv sweep.csv
[ "$(cksum < sweep.csv)" = "$sum" ] && ok || ko "refused sweep changed sweep.csv"
cp sweep.png other.png
bad "sweep png exists" "'other.png' exists; give --overwrite" $swp --csv other.csv
[ ! -e other.csv ] && ok || ko "refused sweep wrote other.csv"
"$spall" penetrate $swp --csv sweep.csv --overwrite >/dev/null 2>&1 && ok || ko "sweep --overwrite"
[ "$(grep -vc '^#' sweep.csv)" -eq 10 ] && ok || ko "sweep --overwrite rows"
bad "trajectory csv exists" "exists; give --overwrite" poncelet $gel --csv traj.csv
"$spall" penetrate mcg --diameter 1e-3 --v0 1000 --projectile steel --target sebs --eta 1e-4 --R 25e6 \
    >/dev/null 2>warn.txt && grep -q "Re = " warn.txt && ok || ko "Re warning"

# examples/pen_sweep (issue 7 item 7): velocity x diameter tables, the
# P_max/d tables (one row per v0, one column per d) and the PNG plots
bash "$src/examples/pen_sweep/pen_sweep.sh" "$spall" sw > sw.txt 2>&1 || { ko "pen_sweep.sh"; cat sw.txt; }
[ "$(grep -vc '^#' sw/gelatin.csv)" -eq 88 ] && ok || ko "pen_sweep gelatin rows (3 d x 29 v0)"
[ "$(grep -vc '^#' sw/sebs.csv)" -eq 176 ] && ok || ko "pen_sweep sebs rows (5 d x 35 v0)"
[ "$(grep -vc '^#' sw/sebs_poncelet.csv)" -eq 176 ] && ok || ko "pen_sweep sebs_poncelet rows"
grep -q '^v0,d=11,d=13,d=16,d=20,d=22$' sw/sebs_table.csv && ok || ko "pen_sweep table header"
[ "$(grep -vc '^#' sw/sebs_table.csv)" -eq 36 ] && ok || ko "pen_sweep table rows"
# the table is the long form's P_max/d: d = 16 um, v0 = 450 m/s both ways
long=$(awk -F, '$1 + 0 == 16e-6 && $2 + 0 == 450 { printf "%.6g", $6 }' sw/sebs.csv)
wide=$(awk -F, '$1 == "450" { print $4 }' sw/sebs_table.csv)
[ -n "$long" ] && [ "$long" = "$wide" ] && ok || ko "pen_sweep table value ($long vs $wide)"
for f in gelatin sebs sebs_poncelet; do
    [ "$(head -c 4 sw/$f.png | tail -c 3)" = "PNG" ] && ok || ko "pen_sweep $f.png"
done
bash "$src/examples/pen_sweep/pen_sweep.sh" "$tmp/nope" sw2 >/dev/null 2>&1; [ $? -eq 2 ] && ok || ko "pen_sweep missing spall"
bash "$src/examples/pen_sweep/pen_sweep.sh" "$spall" sw >/dev/null 2>&1; [ $? -eq 2 ] && ok || ko "pen_sweep into its own results"

bad "unknown mode" "unknown mode" bogus
bad "bad number" "--diameter needs a number" poncelet --diameter x
bad "negative R" "R must be" poncelet --diameter 1e-5 --v0 100 --rho-projectile 1 --rho-target 1 --Cd 0.4 --R -3
bad "no densities" "densities" poncelet --diameter 1e-5 --v0 100 --Cd 0.4 --R 3
bad "unknown option" "unknown option" poncelet --frobnicate 3
# old spellings are refused with the new name (one convention across commands)
bad "old --d" "renamed --diameter" poncelet --d 1e-5 --v0 100
bad "old --rho-p" "renamed --rho-projectile" poncelet --rho-p 1
bad "old --rho-t" "renamed --rho-target" poncelet --rho-t 1
bad "old --cd" "renamed --Cd" poncelet --cd 0.4
bad "old --cv" "renamed --Cv" liu --cv 2e4
bad "diameter and radius" "one of --diameter and --radius" poncelet --diameter 1e-5 --radius 5e-6
bad "fit without data" "exactly one of" fit --model poncelet --rho-projectile 1 --rho-target 1
bad "fit missing file" "cannot open" fit --model poncelet --points nope.csv --rho-projectile 1 --rho-target 1
printf 'd,v0\n1e-5,100\n' > pts.csv
bad "fit missing column" "no column 'P_max'" fit --model poncelet --points pts.csv --rho-projectile 1 --rho-target 1
printf 'd,v0,P_max\n1e-5,100,x\n' > pts2.csv
bad "fit bad cell" "pts2.csv:2:" fit --model poncelet --points pts2.csv --rho-projectile 1 --rho-target 1
bad "sweep range" "FROM:TO:STEP" sweep --model poncelet --diameter 1e-5 --v0 5:1:1 --rho-projectile 1 --rho-target 1 --Cd 1 --R 1 --csv s.csv
bad "unknown model" "unknown penetration model" sweep --model xx --diameter 1e-5 --v0 1:2:1 --rho-projectile 1 --rho-target 1 --csv s.csv

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
