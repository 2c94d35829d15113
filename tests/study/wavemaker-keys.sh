#!/bin/sh
# A wave maker's motion as keys for bw-sim (docs/scene.md, "Moving solids"): a piston's
# velocity (`motion = "FILE"`, rows t,vx,vy,vz) or a flap's angular velocity
# (`angular_motion = "FILE"`, rows t,omega), for regular waves of one period
# (Makefile.scenes `wavemaker`, examples/wavemaker-piston.toml and wavemaker-flap.toml).
#
#   piston  its displacement along +x (into the flume) is
#             X(t) = r(t) (S/2) sin(omega t)
#           so that its stroke, the whole excursion, is S once the ramp is over; the
#           rows are vx = dX/dt, differentiated analytically.
#   flap    hinged at the floor (the pivot), depth h of water over it; its angle is
#             theta(t) = r(t) theta0 sin(omega t),  theta0 = atan((S/2) / h)
#           so that it sweeps S at the still water level; positive theta turns its
#           top toward +x: about the axis +y (right-hand rule), omega = dtheta/dt.
#
# omega = 2 pi / T. The ramp r(t) = (1 - cos(pi t / t_ramp)) / 2 for t < t_ramp =
# RAMP periods, 1 after: the amplitude of the displacement (or angle) grows from 0,
# so the paddle oscillates about where it started (a velocity ramped instead would
# leave it displaced), and it starts at rest. KEYS rows a period from t = 0 to
# DURATION; bw-sim interpolates the velocity linearly between rows and integrates
# it exactly, which puts the paddle within (2 pi / KEYS)^2 / 12 of the amplitude
# (0.2% at 40 keys). A last row at DURATION stops the paddle (bw-sim holds the last
# row's velocity): give a DURATION at least the run's end.
#
#   wavemaker-keys.sh piston|flap --period T --stroke S [--ramp N] [--duration D]
#                     [--keys N] [--depth H] > keys.csv
#
# Defaults: --ramp 2 (periods), --duration 10 (s), --keys 40 (a period), --depth 0.5
# (m; the flap's pivot below the still water level, unused by the piston).
set -eu

die() { echo "wavemaker-keys: $*" >&2; exit 2; }
usage="usage: wavemaker-keys.sh piston|flap --period T --stroke S [--ramp N] [--duration D] [--keys N] [--depth H]"

[ $# -ge 1 ] || die "$usage"
kind=$1
shift
case $kind in
  piston | flap) ;;
  -h | --help) echo "$usage"; exit 0 ;;
  *) die "$kind: expected piston or flap ($usage)" ;;
esac
period='' stroke='' ramp=2 duration=10 keys=40 depth=0.5
while [ $# -gt 0 ]; do
  [ $# -ge 2 ] || die "$1: needs a value ($usage)"
  case $1 in
    --period) period=$2 ;;
    --stroke) stroke=$2 ;;
    --ramp) ramp=$2 ;;
    --duration) duration=$2 ;;
    --keys) keys=$2 ;;
    --depth) depth=$2 ;;
    *) die "$1: unknown option ($usage)" ;;
  esac
  shift 2
done
[ -n "$period" ] || die "--period is required ($usage)"
[ -n "$stroke" ] || die "--stroke is required ($usage)"
positive() {
  echo "$2" | awk '$0 ~ /^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ && $0 + 0 > 0 { ok = 1 } END { exit !ok }' \
    || die "$1 $2: expected a positive number"
}
positive --period "$period"
positive --stroke "$stroke"
positive --duration "$duration"
positive --depth "$depth"
echo "$ramp" | awk '$0 ~ /^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ { ok = 1 } END { exit !ok }' \
  || die "--ramp $ramp: expected a number of periods, 0 or more"
echo "$keys" | awk '$0 ~ /^[0-9]+$/ && $0 + 0 >= 4 { ok = 1 } END { exit !ok }' \
  || die "--keys $keys: expected a whole number of rows a period, at least 4"

awk -v kind="$kind" -v T="$period" -v S="$stroke" -v nramp="$ramp" -v D="$duration" -v nkeys="$keys" \
    -v h="$depth" 'BEGIN {
  pi = atan2(0, -1)
  w = 2 * pi / T
  tr = nramp * T
  if (kind == "piston") { a = S / 2; unit = "m"; what = "displacement X(t) along +x" }
  else { a = atan2(S / 2, h); unit = "rad"; what = "angle theta(t) about +y, pivot on the floor" }
  printf "# %s wave maker: period %.9g s, stroke %.9g m at the still water level", kind, T, S
  if (kind == "flap") printf " (depth %.9g m over the pivot)", h
  printf "\n# %s = r(t) %.9g %s sin(2 pi t / %.9g)\n", what, a, unit, T
  printf "# ramp r(t) = (1 - cos(pi t / %.9g)) / 2 up to %.9g s (%.9g periods), then 1\n", tr, tr, nramp
  printf "# %d rows a period to %.9g s, then one that stops it\n", nkeys, D
  if (kind == "piston") print "t,vx,vy,vz"; else print "t,omega"
  dt = T / nkeys
  n = int(D / dt + 1e-9)
  for (i = 0; i <= n + 1; ++i) {
    t = i * dt
    if (i == n + 1) { if (D - n * dt < 1e-9 * T) break; t = D }
    if (t < tr) { r = (1 - cos(pi * t / tr)) / 2; dr = pi / (2 * tr) * sin(pi * t / tr) }
    else { r = 1; dr = 0 }
    v = a * (dr * sin(w * t) + r * w * cos(w * t))
    if (kind == "piston") printf "%.9g,%.9g,0,0\n", t, v; else printf "%.9g,%.9g\n", t, v
  }
  if (kind == "piston") printf "%.9g,0,0,0\n", D; else printf "%.9g,0\n", D
}'
