#!/usr/bin/env python3
"""Our walls and rooms (bimloc extract's building.json) against web-ifc's (check_ifc.mjs).

A wall is a box to bimloc: its axis from start to end, its thickness across, its height up. Every
wall web-ifc builds must be one of ours (by GlobalId) or named in a warning; for each, the two
boxes' extents must agree within 5 mm across the wall (where its faces stand: what the localizer
matches) and in height, and along the wall within 5 mm or within the wall's thickness at a corner
(the block where two walls meet belongs to one of them: web-ifc keeps it in the wall's mesh, the
box may leave it to the other wall). Walls bimloc marks `approximated` (no box fits them) are
counted, not compared. Every IfcSpace web-ifc builds must be one of our rooms (by GlobalId) or
named in a warning, its footprint's extents in x and y, its floor and its height within 5 mm of
the space's mesh.
usage: compare_plan.py BUILDING_JSON WEBIFC_JSON   (exit 0 agree, 1 disagree)
"""
import json, math, sys

TOL_M = 0.005


def main():
    ours = json.load(open(sys.argv[1]))
    web = json.load(open(sys.argv[2]))['walls']
    by_id = {w['id']: w for s in ours['storeys'] for w in s['walls']}
    warned = ' '.join(ours.get('warnings', []))
    bad, compared, corners, approximated, named = [], 0, 0, 0, 0
    for w in web:
        o = by_id.get(w['id'])
        if o is None:
            named += w['id'] in warned
            if w['id'] not in warned:
                bad.append(f"{w['id']} '{w['name']}': web-ifc builds it, bimloc has no such wall and no warning names it")
            continue
        if o.get('approximated'):
            approximated += 1
            continue
        sx, sy, sz = o['start']
        ex, ey, _ = o['end']
        length = math.hypot(ex - sx, ey - sy)
        if length == 0:
            bad.append(f"{w['id']}: zero-length axis")
            continue
        ux, uy = (ex - sx) / length, (ey - sy) / length
        # web-ifc's mesh in the wall's frame: its vertices' extents along and across the axis.
        along = [(x - sx) * ux + (y - sy) * uy for x, y in w['xy']]
        across = [-(x - sx) * uy + (y - sy) * ux for x, y in w['xy']]
        compared += 1
        t = o['thickness_m']
        errors = {
            'across': max(abs(min(across) + 0.5 * t), abs(max(across) - 0.5 * t)),
            'bottom': abs(w['lo'][2] - sz),
            'top': abs(w['hi'][2] - (sz + o['height_m'])),
        }
        ends = (abs(min(along) - 0.0), abs(max(along) - length))
        if max(ends) > TOL_M:
            corners += 1
            errors['along'] = max(0.0, max(ends) - t)
        worst = max(errors, key=errors.get)
        if errors[worst] > TOL_M:
            bad.append(f"{w['id']} '{w['name']}': {worst} off by {errors[worst]:.3f} m")
    rooms = {r['id']: r for s in ours['storeys'] for r in s['rooms']}
    spaces = json.load(open(sys.argv[2])).get('spaces', [])
    for sp in spaces:
        r = rooms.get(sp['id'])
        if r is None:
            if sp['id'] not in warned:
                bad.append(f"space {sp['id']} '{sp['name']}': web-ifc builds it, bimloc has no such room and no warning names it")
            continue
        xs = [p[0] for p in r['footprint']]
        ys = [p[1] for p in r['footprint']]
        errors = {'x': max(abs(min(xs) - sp['lo'][0]), abs(max(xs) - sp['hi'][0])),
                  'y': max(abs(min(ys) - sp['lo'][1]), abs(max(ys) - sp['hi'][1])),
                  'floor': abs(r['floor_z_m'] - sp['lo'][2]), 'height': abs(r['height_m'] - (sp['hi'][2] - sp['lo'][2]))}
        worst = max(errors, key=errors.get)
        if errors[worst] > TOL_M:
            bad.append(f"space {sp['id']} '{sp['name']}': {worst} off by {errors[worst]:.3f} m")
    print(f"{len(spaces)} spaces, {len(web)} walls built by web-ifc: {compared} compared, {corners} of them differ by a corner block, "
          f"{approximated} approximated by bimloc, {named} left out with a warning; {len(bad)} disagree")
    for b in bad:
        print('  ' + b)
    if compared == 0 and web:
        print('  nothing compared')
        return 1
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
