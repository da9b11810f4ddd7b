#!/usr/bin/env python3
"""Byte-level damage probe of every input bimloc reads (a long check, not a test).

The fuzz tests (tests/test_fuzz.cpp, tests/test_ros2_fuzz.cpp) damage inputs line by line and
record by record; this probe flips, zeroes, cuts and duplicates raw bytes anywhere, and writes
VLP-16 packets' fields out of the manual's ranges. It makes its own clean inputs (a 3 s
simulation of the default world as a ROS 1 bag, an MCAP and a SQLite3 bag, with packets), then
for each damaged copy runs the command that reads it and flags:
  - a crash (a signal) or a hang (no exit within the time limit);
  - an exit status outside the documented ones (0, 1, 2);
  - a refusal (status 2) whose message does not name the damaged file;
  - a message that is not valid UTF-8.
Usage: scripts/damage_probe.py BIMLOC WORKDIR [--seed S] [--cases N] [--kinds k1,k2] [--verbose]
Kinds: ros1 mcap sqlite3 (bags, clouds and packets topics), packets (VLP-16 fields out of
range), tum (bimloc eval), config (--config YAML), pcd (a dataset folder's cloud), ifc
(bimloc extract), ifcnum (one number made extreme: extract and a 2 s run), ifc43 (the same plan written as IFC 4.3 writes it), meta (a rosbag2 metadata.yaml), report (bimloc report merge shards).
Exit status: 0 nothing flagged, 1 something flagged (listed), 2 bad arguments.
"""
import argparse, os, random, re, shutil, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PLAN = os.path.join(ROOT, 'worlds', 'site_office.ifc')


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('bimloc'); ap.add_argument('workdir')
    ap.add_argument('--seed', type=int, default=1); ap.add_argument('--cases', type=int, default=10)
    ap.add_argument('--kinds', default='ros1,mcap,sqlite3,packets,tum,config,pcd,ifc,ifcnum,ifc43,meta,report')
    ap.add_argument('--verbose', action='store_true')
    a = ap.parse_args()
    B, W, rng = os.path.abspath(a.bimloc), os.path.abspath(a.workdir), random.Random(a.seed)
    os.makedirs(W, exist_ok=True)
    flagged = []

    def run(cmd, timeout=180):
        try:
            r = subprocess.run(cmd, capture_output=True, timeout=timeout)
            return r.returncode, r.stderr
        except subprocess.TimeoutExpired:
            return 'HANG', b''

    def check(label, cmd, named, error_status=2):
        rc, err = run(cmd)
        try:
            text = err.decode('utf-8')
            utf8 = True
        except UnicodeDecodeError:
            text, utf8 = err.decode('utf-8', 'replace'), False
        bad = rc == 'HANG' or rc < 0 or rc > 2 or not utf8 or (rc == error_status and named not in text)
        if bad:
            flagged.append(f'{label}: status {rc}{"" if utf8 else " (stderr not UTF-8)"}: {text.strip()[:300]}')
        if bad or a.verbose:
            print(f'{"FLAGGED " if bad else ""}{label}: status {rc}: {text.strip()[:200]}', flush=True)

    def damage(data, kind=None):
        d = bytearray(data)
        kind = kind or rng.choice(['flip', 'flips', 'trunc', 'zero', 'ff', 'dup', 'cut', 'insert'])
        if not d:
            return bytes(d), 'empty'
        p = rng.randrange(len(d))
        if kind == 'flip': d[p] ^= 1 << rng.randrange(8)
        elif kind == 'flips':
            for _ in range(rng.randint(2, 50)): d[rng.randrange(len(d))] = rng.randrange(256)
        elif kind == 'trunc': d = d[:p]
        elif kind == 'zero': d[p:p + 64] = bytes(len(d[p:p + 64]))
        elif kind == 'ff': d[p:p + 16] = b'\xff' * len(d[p:p + 16])
        elif kind == 'dup': d[p:p] = d[p:p + rng.randint(1, 200)]
        elif kind == 'cut': del d[p:p + rng.randint(1, 200)]
        elif kind == 'insert': d[p:p] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 20)))
        return bytes(d), f'{kind} at byte {p}'

    # Clean inputs.
    scenario = os.path.join(W, 'probe.yaml')
    with open(scenario, 'w') as f:
        f.write(f'name: probe\nworld: {PLAN}\nstart: {{room: R101, yaw_deg: 90}}\nmotion: {{type: tour, rooms: [C100]}}\n'
                'duration_s: 3\nodometry: {preset: legged}\nseed: 5\n')
    bags = {}
    for fmt in ('ros1', 'mcap', 'sqlite3'):
        out = os.path.join(W, 'clean_' + fmt)
        if not os.path.isdir(out):
            subprocess.run([B, 'simulate', scenario, '--out', out, '--packets', '--format', fmt, '--quiet'], check=True)
        bags[fmt] = os.path.join(out, 'dataset.bag') if fmt == 'ros1' else \
            os.path.join(out, 'rosbag2', 'rosbag2_0.' + ('mcap' if fmt == 'mcap' else 'db3'))
    kinds = a.kinds.split(',')

    for fmt in ('ros1', 'mcap', 'sqlite3'):
        if fmt not in kinds: continue
        data = open(bags[fmt], 'rb').read()
        for _ in range(a.cases):
            d, how = damage(data, rng.choice(['flip', 'flips', 'zero', 'ff']))
            f = os.path.join(W, 'damaged.' + bags[fmt].rsplit('.', 1)[1])
            open(f, 'wb').write(d)
            for topic in ([], ['--cloud-topic', '/velodyne_packets']):
                check(f'{fmt} {how} {" ".join(topic)}', [B, 'localize', f, '--plan', PLAN] + topic, f)
    if 'packets' in kinds:
        data = open(bags['ros1'], 'rb').read()
        starts = [m.start() for m in re.finditer(b'\xff\xee', data)]
        packets = [s for s in starts if all(data[s + 100 * k:s + 100 * k + 2] == b'\xff\xee' for k in range(12))]
        for kind in ('flag', 'azimuth', 'mode', 'product', 'stamp', 'distance', 'all_ff', 'all_zero'):
            d = bytearray(data)
            for s in rng.sample(packets, min(20, len(packets))):
                b = s + 100 * rng.randrange(12)
                if kind == 'flag': d[b + 1] = 0
                elif kind == 'azimuth': d[b + 2:b + 4] = b'\xff\xff'
                elif kind == 'mode': d[s + 1204] = 0x99
                elif kind == 'product': d[s + 1205] = 0x77
                elif kind == 'stamp': d[s + 1200:s + 1204] = b'\xff' * 4
                elif kind == 'distance':
                    for c in range(32): d[b + 4 + 3 * c:b + 6 + 3 * c] = b'\xff\xff'
                else: d[s:s + 1206] = (b'\xff' if kind == 'all_ff' else b'\x00') * 1206
            f = os.path.join(W, 'packets.bag')
            open(f, 'wb').write(d)
            rc, err = run([B, 'localize', f, '--plan', PLAN, '--cloud-topic', '/velodyne_packets'])
            # Every kind is either refused (2) or said in a warning: never silent.
            if rc == 'HANG' or rc not in (0, 1, 2) or (rc == 2 and f.encode() not in err) or (rc != 2 and b'warning' not in err):
                flagged.append(f'packets {kind}: status {rc}: {err.decode("utf-8", "replace").strip()[:300]}')
                print(f'FLAGGED packets {kind}: status {rc}', flush=True)
            elif a.verbose:
                print(f'packets {kind}: status {rc}: {err.decode("utf-8", "replace").strip()[:200]}')
    clean = os.path.join(W, 'clean_ros1')
    if 'tum' in kinds:
        truth = os.path.join(clean, 'ground_truth.tum')
        for _ in range(a.cases):
            d, how = damage(open(truth, 'rb').read())
            f = os.path.join(W, 'damaged.tum'); open(f, 'wb').write(d)
            check(f'tum {how}', [B, 'eval', truth, f], f, error_status=1)
    if 'config' in kinds:
        text = b'pf:\n  particles: 800\n  evidence_faces: 2\nplanes:\n  ransac_iterations: 200\n'
        for _ in range(a.cases):
            d, how = damage(text)
            f = os.path.join(W, 'damaged.yaml'); open(f, 'wb').write(d)
            check(f'config {how}', [B, 'localize', bags['ros1'], '--plan', PLAN, '--config', f], f)
    if 'pcd' in kinds:
        pcds = sorted(x for x in os.listdir(os.path.join(clean, 'clouds')) if x.endswith('.pcd'))
        for _ in range(a.cases):
            ds = os.path.join(W, 'dataset')
            shutil.rmtree(ds, ignore_errors=True)
            shutil.copytree(clean, ds, ignore=shutil.ignore_patterns('*.bag', '*.pcap'))
            name = rng.choice(pcds)
            d, how = damage(open(os.path.join(clean, 'clouds', name), 'rb').read())
            open(os.path.join(ds, 'clouds', name), 'wb').write(d)
            check(f'pcd {name} {how}', [B, 'localize', ds, '--plan', PLAN], ds)
    if 'ifc' in kinds:
        for _ in range(a.cases):
            d, how = damage(open(PLAN, 'rb').read())
            f = os.path.join(W, 'damaged.ifc'); open(f, 'wb').write(d)
            check(f'ifc {how}', [B, 'extract', f], f, error_status=1)
    if 'ifcnum' in kinds:
        # One number of the plan (a coordinate, a length, a storey's Elevation) made extreme, as a
        # unit slip or a damaged export writes it, then extracted and run for 2 s: the byte
        # damage above rarely leaves a parsable number far out (a storey at -1e300 aborted the
        # ray caster; a wall 1e9 m long overflowed the path grid's count).
        text = open(PLAN, 'rb').read()
        numbers = [m.span() for m in re.finditer(rb'(?<=[(,])-?\d+\.\d*(?:E[-+]?\d+)?(?=[,)])', text)]
        extremes = [b'1.E9', b'-1.E9', b'1.E15', b'1.E300', b'-1.E300', b'0.', b'1.E-12', b'-0.', b'1.E30', b'123456.']
        for _ in range(a.cases):
            (s0, s1), v = rng.choice(numbers), rng.choice(extremes)
            f = os.path.join(W, 'extreme.ifc'); open(f, 'wb').write(text[:s0] + v + text[s1:])
            how = f'{v.decode()} at byte {s0}'
            check(f'ifcnum extract {how}', [B, 'extract', f], f, error_status=1)
            check(f'ifcnum run {how}', [B, 'run', '--plan', f, '--all-rooms', '--rooms', 'R101', '--duration', '2', '--jobs', '1'], f)
    if 'ifc43' in kinds:
        # The plan as IFC 4.3 writes it: its FILE_SCHEMA, and a TagList on every point list
        # (what the reader rewrites to IFC4's attributes, localizer/src/bim/ifc4x3.hpp).
        text = open(PLAN, 'rb').read().replace(b"FILE_SCHEMA(('IFC4'))", b"FILE_SCHEMA(('IFC4X3_ADD2'))")
        text = re.sub(rb'(IFCCARTESIANPOINTLIST[23]D\((?:[^;]*?))\);', rb'\1,$);', text)
        for _ in range(a.cases):
            d, how = damage(text)
            f = os.path.join(W, 'damaged43.ifc'); open(f, 'wb').write(d)
            check(f'ifc43 {how}', [B, 'extract', f], f, error_status=1)
    if 'meta' in kinds:
        meta = os.path.join(W, 'clean_mcap', 'rosbag2', 'metadata.yaml')
        for _ in range(a.cases):
            r2 = os.path.join(W, 'rosbag2'); shutil.rmtree(r2, ignore_errors=True); os.makedirs(r2)
            shutil.copy(bags['mcap'], r2)
            d, how = damage(open(meta, 'rb').read())
            open(os.path.join(r2, 'metadata.yaml'), 'wb').write(d)
            check(f'metadata.yaml {how}', [B, 'localize', r2, '--plan', PLAN], r2)
    if 'report' in kinds:
        shards = []
        for k in (1, 2):
            f = os.path.join(W, f'shard{k}.json')
            with open(f, 'wb') as out:
                subprocess.run([B, 'run', '--plan', PLAN, '--all-rooms', '--rooms', 'R101,R102', '--duration', '2',
                                '--shard', f'{k}/2', '--json', '--jobs', '1'], stdout=out, stderr=subprocess.DEVNULL)
            shards.append(f)
        for _ in range(a.cases):
            d, how = damage(open(shards[1], 'rb').read())
            f = os.path.join(W, 'damaged_shard.json'); open(f, 'wb').write(d)
            check(f'report {how}', [B, 'report', 'merge', shards[0], f], f)
    print(f'{len(flagged)} flagged')
    for line in flagged: print('  ' + line)
    return 1 if flagged else 0


if __name__ == '__main__':
    sys.exit(main())
