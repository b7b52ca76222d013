# stanford-bunny.obj with cylindrical texture coordinates around the y axis
# (u the angle, v the height; a seam where the angle wraps, the faces across it
# given u + 1 on their low side): BENCHMARKS.md, "Attributes in the lossless mode".
# Usage: python3 cylinder_uv_bunny.py stanford-bunny.obj bunny-cyl.obj
import math, sys
src, dst = sys.argv[1], sys.argv[2]
vs, fs = [], []
for line in open(src):
    p = line.split()
    if not p: continue
    if p[0] == 'v': vs.append(tuple(map(float, p[1:4])))
    elif p[0] == 'f': fs.append([int(x.split('/')[0]) - 1 for x in p[1:]])
cx = sum(v[0] for v in vs) / len(vs); cz = sum(v[2] for v in vs) / len(vs)
lo = min(v[1] for v in vs); hi = max(v[1] for v in vs)
uv = [] ; key = {}
out_f = []
for f in fs:
    us = [(math.atan2(vs[i][2] - cz, vs[i][0] - cx) / (2 * math.pi)) % 1.0 for i in f]
    # a face straddling the seam takes u + 1 on its low side (a second value there)
    if max(us) - min(us) > 0.5:
        us = [u + 1.0 if u < 0.5 else u for u in us]
    idx = []
    for i, u in zip(f, us):
        k = (i, u > 1.0 or (u >= 0.5 and max(us) > 1.0))
        if k not in key:
            key[k] = len(uv); uv.append((u, (vs[i][1] - lo) / (hi - lo)))
        idx.append(key[k])
    out_f.append((f, idx))
with open(dst, 'w') as o:
    for v in vs: o.write('v %r %r %r\n' % v)
    for u in uv: o.write('vt %r %r\n' % u)
    for f, t in out_f: o.write('f ' + ' '.join('%d/%d' % (a + 1, b + 1) for a, b in zip(f, t)) + '\n')
