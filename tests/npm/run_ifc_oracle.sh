#!/bin/sh
# The walls and rooms bimloc extracts against web-ifc's (ctest ifc_npm_oracle): That Open
# Company's IFC reader (web-ifc, an implementation of its own, with IFC2X3, IFC4 and IFC4X3
# schemas) builds each IfcWall's and IfcSpace's mesh (check_ifc.mjs) and compare_plan.py holds
# our wall boxes and room footprints to them, for the project's
# plans (worlds/), the shared real plans where ../shared is present, and every IFC4 one of them
# again as IFC 4.3 (its FILE_SCHEMA IFC4X3_ADD2: read by web-ifc as 4.3, by bimloc through IFC4).
# Exit 77 (ctest SKIP_RETURN_CODE) where npm is missing or cannot reach its registry.
# usage: run_ifc_oracle.sh BIMLOC WORK_DIR WORLDS_DIR [SHARED_IFC_DIR]
set -u
BIMLOC=$1 WORK=$2 WORLDS=$3 SHARED=${4:-}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)
PACKAGE="web-ifc@0.0.78"
if [ ! -f "$WORK/node_modules/web-ifc/package.json" ]; then
  command -v npm >/dev/null 2>&1 || { echo "SKIP: npm is not installed (apt-get install npm)"; exit 77; }
  command -v node >/dev/null 2>&1 || { echo "SKIP: node is not installed"; exit 77; }
  if ! timeout 900 npm install --no-audit --no-fund --prefix "$WORK" $PACKAGE >"$WORK/npm.log" 2>&1; then
    echo "SKIP: npm cannot install $PACKAGE (no registry?):"; tail -5 "$WORK/npm.log"; exit 77
  fi
fi
cp "$HERE/check_ifc.mjs" "$WORK/check_ifc.mjs"  # resolves web-ifc from WORK's node_modules
failed=0
check() {  # check PLAN NAME
  rm -rf "$WORK/out_$2"
  if ! "$BIMLOC" extract "$1" --out "$WORK/out_$2" >/dev/null 2>"$WORK/extract_$2.err"; then
    echo "FAILED: bimloc extract $1:"; cat "$WORK/extract_$2.err"; failed=1; return
  fi
  if ! node "$WORK/check_ifc.mjs" "$1" >"$WORK/web_$2.json" 2>"$WORK/web_$2.err"; then
    echo "FAILED: web-ifc on $1:"; tail -3 "$WORK/web_$2.err"; failed=1; return
  fi
  printf '%s: ' "$2"
  python3 "$HERE/compare_plan.py" "$WORK/out_$2/building.json" "$WORK/web_$2.json" || failed=1
}
plans=$(ls "$WORLDS"/*.ifc)
if [ -n "$SHARED" ] && [ -d "$SHARED" ]; then plans="$plans $(ls "$SHARED"/*.ifc)"; else echo "note: no shared plans ($SHARED): the project's plans only"; fi
for plan in $plans; do
  name=$(basename "$plan" .ifc)
  check "$plan" "$name"
  if grep -q "FILE_SCHEMA *(('IFC4'))" "$plan"; then
    sed "s/FILE_SCHEMA *(('IFC4'))/FILE_SCHEMA(('IFC4X3_ADD2'))/" "$plan" >"$WORK/${name}_ifc43.ifc"
    check "$WORK/${name}_ifc43.ifc" "${name}_ifc43"
  fi
done
[ $failed -eq 0 ] && echo "PASSED: every wall and space web-ifc builds is bimloc's, within 5 mm" || echo "FAILED"
exit $failed
