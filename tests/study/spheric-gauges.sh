#!/usr/bin/env bash
# SPHERIC Test 2's wave gauges (Makefile.scenes `spheric2`, docs/validation.md "Impact
# pressure"): the water's depth at the experiment's gauges from the frames (bw-measure
# gauge --at H2=0.992,0.5 --at H4=2.638,0.5 --bottom 0: per gauge the top of the water
# column over its line, the highest particle's centre, NaN when dry; the depth is that
# plus half a spacing, the particle's own layer, and 0 when dry) against the
# experiment's histories (examples/data/spheric-test2-histories.csv), each gauge the
# experiment's column of its name. Per gauge
#   arrival   where the experiment starts dry, the first time the depth reaches
#             10, 20 and 50 mm, against the experiment's: how late the thin front
#             and the body of the flow behind it come
#   rms, bias the RMS and the mean of the depth's difference over 0.15-0.7 s (the
#             experiment interpolated to the frames' times): at H4 the reservoir
#             draining, at H2 the flow toward the box and, from 0.45 s, the bore
#             it throws back
# Writes PREFIX.csv (one row per gauge), PREFIX.md (a Markdown table, also printed)
# and PREFIX.png.
#
#   spheric-gauges.sh spheric-test2-histories.csv gauges.csv PREFIX SPACING
set -euo pipefail

die() { echo "spheric-gauges: $*" >&2; exit 2; }
[[ $# -eq 4 ]] || die "usage: spheric-gauges.sh spheric-test2-histories.csv gauges.csv PREFIX SPACING"
histories=$1 gauges=$2 prefix=$3 spacing=$4
[[ -s $histories ]] || die "$histories: missing or empty"
[[ -s $gauges ]] || die "$gauges: missing or empty (bw-measure gauge's output)"
[[ $spacing =~ ^[0-9.]+$ ]] || die "$spacing: expected the spacing in m"
IFS=, read -r -a names < "$gauges"
[[ ${names[0]} == time && ${#names[@]} -ge 2 ]] || die "$gauges: expected the columns time,NAME,... of bw-measure gauge"

echo "gauge,spacing,t10_s,t10_exp_s,t10_error_ms,t20_s,t20_exp_s,t20_error_ms,t50_s,t50_exp_s,t50_error_ms,rms_m,bias_m" > "$prefix.csv.tmp"
plot=""
for ((c = 1; c < ${#names[@]}; ++c)); do
  name=${names[c]}
  grep -q "^time,.*\b$name\b" "$histories" || die "$histories: has no column $name (the gauge's name in $gauges)"
  awk -v OFS=, -v name="$name" -v spacing="$spacing" -v file="$gauges" -v gcol=$((c + 1)) '
    BEGIN { split("0.01 0.02 0.05", level, " ") }
    FILENAME == ARGV[1] {
      if ($0 ~ /^#/) next
      n = split($0, v, ",")
      if (v[1] == "time") { for (c = 2; c <= n; ++c) if (v[c] == name) col = c; next }
      ++rows; et[rows] = v[1]; eh[rows] = v[col]
      for (k = 1; k <= 3; ++k) if (!(k in exp_at) && v[col] >= level[k]) exp_at[k] = v[1]
      next
    }
    FNR == 1 { next }
    {
      split($0, v, ",")
      t = v[1] + 0
      d = (v[gcol] == "nan" || v[gcol] == "-nan") ? 0 : v[gcol] + spacing / 2
      for (k = 1; k <= 3; ++k) if (!(k in run_at) && d >= level[k]) run_at[k] = t
      if (t >= 0.15 && t <= 0.7 && rows > 1) {
        while (j < rows - 1 && et[j + 1] <= t) ++j
        if (j < 1) j = 1
        w = (t - et[j]) / (et[j + 1] - et[j])
        e = eh[j] + w * (eh[j + 1] - eh[j])
        sum += d - e; sum2 += (d - e) * (d - e); count++
      }
    }
    END {
      if (!count) { print "spheric-gauges: " file ": no frame between 0.15 and 0.7 s" > "/dev/stderr"; exit 2 }
      line = name OFS spacing
      dry = eh[1] < 0.005
      for (k = 1; k <= 3; ++k) {
        r = (dry && k in run_at) ? run_at[k] : "nan"
        x = (dry && k in exp_at) ? exp_at[k] : "nan"
        line = line OFS r OFS x OFS ((r != "nan" && x != "nan") ? sprintf("%.1f", (r - x) * 1000) : "nan")
      }
      print line, sprintf("%.4f", sqrt(sum2 / count)), sprintf("%+.4f", sum / count)
    }' "$histories" "$gauges" >> "$prefix.csv.tmp"
  plot+="${plot:+, }\"$gauges\" using 1:(column($((c + 1))) == column($((c + 1))) ? column($((c + 1))) + $spacing / 2 : 0) with lines lw 1.5 title \"$name breakwater\""
  plot+=", \"$histories\" using 1:\"$name\" with lines lw 1.5 lc rgb \"black\" dt (4,2) title \"$name experiment\""
done
mv "$prefix.csv.tmp" "$prefix.csv"

awk -F, '
  function cell(v) { return v == "nan" ? "-" : sprintf("%.4f", v) }
  function ms(v) { return v == "nan" ? "-" : sprintf("%+.1f", v) }
  NR == 1 {
    print "| gauge | 10 mm at (s) | experiment | error (ms) | 20 mm at (s) | experiment | error (ms) | 50 mm at (s) | experiment | error (ms) | RMS 0.15-0.7 s (mm) | bias (mm) |"
    print "|---|---|---|---|---|---|---|---|---|---|---|---|"
    next
  }
  {
    printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.1f | %+.1f |\n", $1, cell($3), cell($4), ms($5), cell($6), \
      cell($7), ms($8), cell($9), cell($10), ms($11), 1000 * $12, 1000 * $13
  }' "$prefix.csv" > "$prefix.md.tmp"
mv "$prefix.md.tmp" "$prefix.md"

if command -v gnuplot >/dev/null; then
  gnuplot <<EOF
set terminal pngcairo size 1000,500 font ",10"
set output "$prefix.png.tmp"
set datafile separator ","
set datafile commentschars "#"
set title "SPHERIC Test 2 at spacing $spacing m: water depth at the gauges"
set xlabel "t (s)"
set ylabel "depth (m)"
set xrange [0.15:0.7]
set key outside right
plot $plot
EOF
  mv "$prefix.png.tmp" "$prefix.png"
fi
cat "$prefix.md"
