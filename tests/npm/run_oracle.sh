#!/bin/sh
# The npm oracle of issue 29 (ctest ros2_npm_oracle): installs Foxglove's MCAP and ROS 2 CDR
# packages into WORK/ with npm, then
#   1. `bimloc simulate --format mcap`: @mcap/core reads our rosbag2_0.mcap (every record and
#      CRC valid, summary and zstd chunk indexes present) and every message decodes, by our
#      ros2msg schemas, to what our reader decodes (ros2_dump);
#   2. `bimloc localize --out` on it: the same for localized.mcap (/tf, /localization, the
#      plan's MarkerArray on /bimloc/plan);
#   3. @mcap/core writes MCAP files (zstd and lz4 chunks, with and without summary): our reader
#      gives back what they wrote.
# Exit 77 (ctest SKIP_RETURN_CODE) where npm is missing or cannot reach its registry.
# usage: run_oracle.sh BIMLOC ROS2_DUMP WORK_DIR PLAN
set -u
BIMLOC=$1 DUMP=$2 WORK=$3 PLAN=$4
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$WORK"
export ORACLE_DIR="$WORK"
PACKAGES="@mcap/core@2.2.2 @mcap/support@1.1.0 @foxglove/rosmsg2-serialization@3.1.0 @foxglove/rosmsg@5.0.5 @foxglove/wasm-zstd lz4js@0.2.0"
if [ ! -f "$WORK/node_modules/lz4js/package.json" ] || [ ! -d "$WORK/node_modules/@mcap/support" ]; then
  command -v npm >/dev/null 2>&1 || { echo "SKIP: npm is not installed (apt-get install npm)"; exit 77; }
  command -v node >/dev/null 2>&1 || { echo "SKIP: node is not installed"; exit 77; }
  if ! timeout 900 npm install --no-audit --no-fund --prefix "$WORK" $PACKAGES >"$WORK/npm.log" 2>&1; then
    echo "SKIP: npm cannot install $PACKAGES (no registry?):"; tail -5 "$WORK/npm.log"; exit 77
  fi
fi
fail() { echo "FAILED: $*"; exit 1; }
cat >"$WORK/s.yaml" <<YAML
name: npm oracle
world: $PLAN
start: {room: C100, yaw_deg: 0}
motion: {type: tour, rooms: [R101]}
duration_s: 6
odometry: {preset: legged}
seed: 3
YAML
rm -rf "$WORK/sim" "$WORK/loc"
"$BIMLOC" simulate "$WORK/s.yaml" --out "$WORK/sim" --format mcap --quiet || fail "bimloc simulate --format mcap"
"$DUMP" "$WORK/sim/rosbag2" >"$WORK/ours.json" || fail "ros2_dump of our bag"
node "$HERE/check_mcap.mjs" read "$WORK/sim/rosbag2/rosbag2_0.mcap" "$WORK/ours.json" || fail "our rosbag2_0.mcap"
"$BIMLOC" localize "$WORK/sim/rosbag2" --plan "$PLAN" --out "$WORK/loc" >"$WORK/localize.log" 2>&1
[ -f "$WORK/loc/localized.mcap" ] || { cat "$WORK/localize.log"; fail "no localized.mcap"; }
"$DUMP" "$WORK/loc/localized.mcap" >"$WORK/ours_localized.json" || fail "ros2_dump of localized.mcap"
node "$HERE/check_mcap.mjs" read "$WORK/loc/localized.mcap" "$WORK/ours_localized.json" || fail "our localized.mcap"
grep -q '"/bimloc/plan"' "$WORK/ours_localized.json" || fail "localized.mcap has no /bimloc/plan"
node "$HERE/check_mcap.mjs" write "$WORK/theirs" || fail "@mcap/core's writer"
for f in zstd_summary zstd_nosummary lz4_summary lz4_nosummary; do
  "$DUMP" "$WORK/theirs_$f.mcap" >"$WORK/ours_theirs_$f.json" || fail "our reader on theirs_$f.mcap"
  node "$HERE/check_mcap.mjs" compare "$WORK/theirs_expected.json" "$WORK/ours_theirs_$f.json" || fail "theirs_$f.mcap"
done
echo "npm oracle: all passed"
