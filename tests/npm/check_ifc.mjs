// The walls and spaces of an IFC plan as web-ifc (That Open Company's reader, an implementation of
// its own with IFC2X3, IFC4 and IFC4X3 schemas) builds them: each IfcWall / IfcWallStandardCase's
// (and IfcSpace's)
// GlobalId, name, the bounding box of its mesh in the plan's frame, z up (web-ifc's meshes are
// y up: x, y, z = x, -z, y), and its vertices' distinct x, y. Printed as one JSON object for
// tests/npm/run_ifc_oracle.sh.
// usage: node check_ifc.mjs PLAN.ifc
import * as WebIFC from 'web-ifc';
import fs from 'fs';

const api = new WebIFC.IfcAPI();
await api.Init();
const model = api.OpenModel(new Uint8Array(fs.readFileSync(process.argv[2])));
const walls = [];
const spaces = [];
for (const type of [WebIFC.IFCWALL, WebIFC.IFCWALLSTANDARDCASE, WebIFC.IFCSPACE]) {
  const ids = api.GetLineIDsWithType(model, type);
  for (let i = 0; i < ids.size(); i++) {
    const id = ids.get(i);
    const line = api.GetLine(model, id);
    const mesh = api.GetFlatMesh(model, id);
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    const xy = new Map();
    for (let g = 0; g < mesh.geometries.size(); g++) {
      const placed = mesh.geometries.get(g);
      const geometry = api.GetGeometry(model, placed.geometryExpressID);
      const v = api.GetVertexArray(geometry.GetVertexData(), geometry.GetVertexDataSize());  // x y z nx ny nz
      const T = placed.flatTransformation;  // column-major 4x4
      for (let k = 0; k < v.length; k += 6) {
        const x = v[k], y = v[k + 1], z = v[k + 2];
        const w = [T[0] * x + T[4] * y + T[8] * z + T[12], T[1] * x + T[5] * y + T[9] * z + T[13], T[2] * x + T[6] * y + T[10] * z + T[14]];
        const zup = [w[0], -w[2], w[1]];
        for (let a = 0; a < 3; a++) lo[a] = Math.min(lo[a], zup[a]), hi[a] = Math.max(hi[a], zup[a]);
        const key = `${zup[0].toFixed(4)},${zup[1].toFixed(4)}`;
        if (!xy.has(key)) xy.set(key, [zup[0], zup[1]]);
      }
      geometry.delete();
    }
    if (Number.isFinite(lo[0]))
      (type === WebIFC.IFCSPACE ? spaces : walls).push({ id: line.GlobalId.value, name: line.Name ? line.Name.value : '', lo, hi, xy: [...xy.values()] });
  }
}
console.log(JSON.stringify({ schema: api.GetModelSchema(model), walls, spaces }));
api.CloseModel(model);
