#!/usr/bin/env bash
# What a sensor's fluctuation is made of (docs/validation.md, "What P1's noise is made
# of"): from a history of samples (bw-measure sensors: time,NAME,... in Pa, each sample
# the mean over its interval), over T0..T1,
#   mean, rms   the samples' mean and the RMS of their departure from it
#   noise       the RMS of the change from one sample to the next over the mean, as
#               spheric-report.sh reads it, with the samples as they are and averaged
#               in runs of 2, 4, 10 and 20 (a sensor sampled that much slower)
#   spectrum    the share of the fluctuation's power in each band of BAND_HZ (a
#               discrete Fourier transform of the samples less their mean)
#   with OTHER  the correlation of the two sensors' fluctuations at periods of 4 to 40
#               samples (the difference of their moving means over 4 and 40 samples)
#               at lags up to 40 samples, and the lag where it is largest (positive:
#               OTHER follows)
#
#   sensor-spectrum.sh sensors.csv NAME T0 T1 [BAND_HZ [OTHER]]
set -euo pipefail

die() { echo "sensor-spectrum: $*" >&2; exit 2; }
[[ $# -ge 4 && $# -le 6 ]] || die "usage: sensor-spectrum.sh sensors.csv NAME T0 T1 [BAND_HZ [OTHER]]"
file=$1 name=$2 t0=$3 t1=$4 band=${5:-20} other=${6:-}
[[ -s $file ]] || die "$file: missing or empty"
number='^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$'
[[ $t0 =~ $number && $t1 =~ $number ]] && awk -v a="$t0" -v b="$t1" 'BEGIN { exit !(b > a) }' ||
  die "T0 '$t0', T1 '$t1': expected times in s with T1 > T0"
[[ $band =~ $number ]] && awk -v b="$band" 'BEGIN { exit !(b > 0) }' || die "BAND_HZ '$band': expected a positive number"
IFS=, read -r -a names < "$file"
column() {
  local c
  for ((c = 1; c < ${#names[@]}; ++c)); do [[ ${names[c]} == "$1" ]] && { echo $((c + 1)); return; }; done
  die "$file: has no column '$1' (its columns: ${names[*]})"
}
[[ ${names[0]} == time ]] || die "$file: expected the columns time,NAME,... of bw-measure sensors"
a=$(column "$name")
b=0
[[ -n $other ]] && b=$(column "$other")

awk -F, -v a="$a" -v b="$b" -v t0="$t0" -v t1="$t1" -v band="$band" -v name="$name" -v other="$other" '
  NR > 1 && $1 + 0 >= t0 && $1 + 0 <= t1 { ++n; t[n] = $1; x[n] = $a; if (b) y[n] = $b }
  function moving(v, k, out,   i, s) {
    s = 0
    for (i = 1; i <= n; ++i) { s += v[i]; if (i > k) s -= v[i - k]; out[i] = s / (i < k ? i : k) }
  }
  END {
    if (n < 8) { print "sensor-spectrum: fewer than 8 samples in " t0 "..." t1 " s" > "/dev/stderr"; exit 2 }
    dt = (t[n] - t[1]) / (n - 1)
    mean = 0; for (i = 1; i <= n; ++i) mean += x[i]; mean /= n
    ss = 0; for (i = 1; i <= n; ++i) ss += (x[i] - mean) ^ 2
    printf "%s: %d samples %.3f ms apart, mean %.1f Pa, rms %.1f Pa\n", name, n, dt * 1000, mean, sqrt(ss / n)
    split("1 2 4 10 20", runs, " ")
    for (r = 1; r <= 5; ++r) {
      k = runs[r]; m = int(n / k)
      if (m < 3 || mean == 0) continue
      d2 = 0
      for (j = 1; j <= m; ++j) { s = 0; for (i = (j - 1) * k + 1; i <= j * k; ++i) s += x[i]; w[j] = s / k }
      for (j = 1; j < m; ++j) d2 += (w[j + 1] - w[j]) ^ 2
      printf "noise over samples of %.2f ms: %.0f%%\n", k * dt * 1000, 100 * sqrt(d2 / (m - 1)) / (mean < 0 ? -mean : mean)
    }
    pi = atan2(0, -1); total = 0
    for (f = 1; f <= int(n / 2); ++f) {
      re = 0; im = 0
      for (i = 1; i <= n; ++i) { p = 2 * pi * f * (i - 1) / n; re += (x[i] - mean) * cos(p); im += (x[i] - mean) * sin(p) }
      power = re * re + im * im
      k = int(f / (n * dt) / band); bands[k] += power; total += power; if (k > top) top = k
    }
    print "band (Hz),share of the power"
    for (k = 0; k <= top; ++k)
      if (total > 0) printf "%g-%g,%.1f%%\n", k * band, (k + 1) * band, 100 * bands[k] / total
    if (!b) exit
    if (n <= 80) { print "correlation with " other ": needs more than the 80 samples of its longest period and lag"; exit }
    moving(x, 4, x4); moving(x, 40, x40); moving(y, 4, y4); moving(y, 40, y40)
    # the first 40 samples hold the start of the long mean
    m = 0; sa = 0; sb = 0; ma = 0; mb = 0
    for (i = 41; i <= n; ++i) { ++m; u[m] = x4[i] - x40[i]; v[m] = y4[i] - y40[i]; ma += u[m]; mb += v[m] }
    ma /= m; mb /= m
    for (i = 1; i <= m; ++i) { u[i] -= ma; v[i] -= mb; sa += u[i] ^ 2; sb += v[i] ^ 2 }
    if (!(sa > 0 && sb > 0)) { print "correlation with " other ": no fluctuation"; exit }
    best = -2
    for (lag = -40; lag <= 40; ++lag) {
      s = 0
      for (i = 1; i <= m; ++i) if (i + lag >= 1 && i + lag <= m) s += u[i] * v[i + lag]
      s /= sqrt(sa * sb)
      if (lag == 0) zero = s
      if (s > best) { best = s; at = lag }
    }
    printf "correlation with %s at periods of %.1f-%.1f ms: %.2f at lag 0, largest %.2f at %+.2f ms\n", other,
           4 * dt * 1000, 40 * dt * 1000, zero, best, at * dt * 1000
  }' "$file"
