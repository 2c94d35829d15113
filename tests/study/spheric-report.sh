#!/usr/bin/env bash
# SPHERIC Test 2's report (Makefile.scenes `spheric2`, docs/validation.md "Impact
# pressure"): from the sensors' histories (bw-measure sensor: time,P1,P2,P3,P4 in Pa)
# and the experiment's table (examples/data/spheric-test2-pressure.txt), per sensor
#   rise     the first time the pressure passes 1 kPa (a tenth of the peaks: the
#            water has reached the sensor), against the experiment's first rise
#   peak     the largest pressure and when, against the experiment's
#   mean, sd the mean and standard deviation over 0.45-0.55 s, where the flow runs
#            steadily up the face and a smooth solver reads a steady load
#   noise    the RMS of the change from one sample to the next over the same span,
#            over the mean: the acoustic noise (a steady load gives 0)
# Writes PREFIX.csv (one row per sensor), PREFIX.md (a Markdown table) and PREFIX.png
# (the four histories with the experiment's rise and peak marked).
#
#   spheric-report.sh sensors.csv spheric-test2-pressure.txt PREFIX SPACING [LABEL=other.csv ...]
# (other runs' sensors drawn in the plot beside the first, e.g. another density scheme;
# SPHERIC_LABEL names the first, "breakwater" by default)
set -euo pipefail

die() { echo "spheric-report: $*" >&2; exit 2; }
[[ $# -ge 4 ]] || die "usage: spheric-report.sh sensors.csv spheric-test2-pressure.txt PREFIX SPACING [LABEL=other.csv ...]"
sensors=$1 reference=$2 prefix=$3 spacing=$4
shift 4
extra=""
for e in "$@"; do
  [[ $e == *=* && -s ${e#*=} ]] || die "$e: expected LABEL=sensors.csv of another run"
  extra+=", \"${e#*=}\" using 1:(column(k+1) / 1000) with lines lw 1 title \"${e%%=*}\""
done
[[ -s $sensors ]] || die "$sensors: missing or empty"
[[ -s $reference ]] || die "$reference: missing or empty"

awk -v OFS=, -v spacing="$spacing" '
  FNR == NR {
    if ($0 ~ /^P[0-9]/) { rise[$1] = $2; peak[$1] = $3 * 1000; peak_time[$1] = $4; sub(/^~/, "", peak_time[$1]) }
    next
  }
  FNR == 1 {
    n = split($0, head, ",")
    next
  }
  {
    split($0, v, ",")
    t = v[1]
    for (c = 2; c <= n; ++c) {
      p = (v[c] == "nan" || v[c] == "-nan") ? 0 : v[c] + 0
      if (!(c in first) && p > 1000) first[c] = t
      if (!(c in best) || p > best[c]) { best[c] = p; best_time[c] = t }
      if (t >= 0.45 && t <= 0.55) {
        sum[c] += p; sum2[c] += p * p; count[c]++
        if (c in last) { d = p - last[c]; jump[c] += d * d; jumps[c]++ }
        last[c] = p
      }
    }
  }
  END {
    print "sensor,spacing,rise_s,rise_exp_s,rise_error_ms,peak_kpa,peak_time_s,peak_exp_kpa,peak_error,mean_kpa,sd_kpa,noise"
    for (c = 2; c <= n; ++c) {
      s = head[c]
      m = count[c] ? sum[c] / count[c] : 0
      var = count[c] ? sum2[c] / count[c] - m * m : 0
      sd = var > 0 ? sqrt(var) : 0
      noise = (jumps[c] && m > 0) ? sqrt(jump[c] / jumps[c]) / m : "nan"
      r = (c in first) ? first[c] : "nan"
      re = (c in first && s in rise) ? (first[c] - rise[s]) * 1000 : "nan"
      pe = (s in peak && peak[s] > 0) ? best[c] / peak[s] - 1 : "nan"
      printf "%s,%s,%s,%s,%s,%.3f,%s,%.3f,%s,%.3f,%.3f,%s\n", s, spacing, r, rise[s], re, best[c] / 1000, best_time[c], \
        peak[s] / 1000, pe, m / 1000, sd / 1000, noise
    }
  }' "$reference" "$sensors" > "$prefix.csv.tmp"
mv "$prefix.csv.tmp" "$prefix.csv"

awk -F, '
  NR == 1 {
    print "| sensor | rise (s) | experiment | error (ms) | peak (kPa) | at (s) | experiment | error | mean 0.45-0.55 s (kPa) | sd | noise |"
    print "|---|---|---|---|---|---|---|---|---|---|---|"
    next
  }
  {
    printf "| %s | %.4f | %.3f | %+.1f | %.2f | %.4f | %.1f | %+.0f%% | %.2f | %.2f | %.0f%% |\n", $1, $3, $4, $5, $6, $7, $8, \
      100 * $9, $10, $11, 100 * $12
  }' "$prefix.csv" > "$prefix.md.tmp"
mv "$prefix.md.tmp" "$prefix.md"

if command -v gnuplot >/dev/null; then
  # The experiment's marks: (rise, 0) and (peak time, peak) per sensor.
  awk -v OFS=, '/^P[0-9]/ { t = $4; sub(/^~/, "", t); print $1, $2, 0; print $1, t, $3 }' "$reference" > "$prefix.exp.tmp"
  gnuplot <<EOF
set terminal pngcairo size 1200,900 font ",10"
set output "$prefix.png.tmp"
set datafile separator ","
set multiplot layout 2,2 title "SPHERIC Test 2 at spacing $spacing m: pressure on the box's face"
do for [k=1:4] {
  set title sprintf("P%d", k)
  set xlabel "t (s)"
  set ylabel "p (kPa)"
  set xrange [0.3:0.7]
  set yrange [-1:*]
  set key top right
  plot "$sensors" using 1:(column(k+1) / 1000) with lines lw 1.5 title "${SPHERIC_LABEL:-breakwater}"$extra, \
       "< grep '^P".k.",' $prefix.exp.tmp" using 2:3 with points pt 7 ps 1.5 lc rgb "black" title "experiment (rise, peak)"
}
unset multiplot
EOF
  mv "$prefix.png.tmp" "$prefix.png"
  rm -f "$prefix.exp.tmp"
fi
