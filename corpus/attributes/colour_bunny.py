# stanford-bunny.obj with a smooth per-vertex RGB colour (uchar), as ASCII PLY:
# the coloured mesh of BENCHMARKS.md, "Attributes in the lossless mode".
# Usage: python3 colour_bunny.py stanford-bunny.obj bunny-colour.ply
import math, sys
src, dst = sys.argv[1], sys.argv[2]
vs, fs = [], []
for line in open(src):
    p = line.split()
    if not p: continue
    if p[0] == 'v': vs.append(tuple(map(float, p[1:4])))
    elif p[0] == 'f': fs.append([int(x.split('/')[0]) - 1 for x in p[1:]])
lo = [min(v[k] for v in vs) for k in range(3)]
hi = [max(v[k] for v in vs) for k in range(3)]
def col(v):
    t = [(v[k] - lo[k]) / (hi[k] - lo[k]) for k in range(3)]
    r = 0.5 + 0.5 * math.sin(6.0 * t[0] + 1.0)
    g = 0.5 + 0.5 * math.sin(5.0 * t[1] + 2.0 * t[2])
    b = 0.5 + 0.5 * math.cos(4.0 * t[2] - 3.0 * t[0])
    return [min(255, int(round(255 * c))) for c in (r, g, b)]
with open(dst, 'w') as o:
    o.write('ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n'
            'property uchar red\nproperty uchar green\nproperty uchar blue\nelement face %d\n'
            'property list uchar int vertex_indices\nend_header\n' % (len(vs), len(fs)))
    for v in vs:
        o.write('%r %r %r %d %d %d\n' % (v + tuple(col(v))))
    for f in fs:
        o.write('%d %s\n' % (len(f), ' '.join(map(str, f))))
