"""Compare hfo2d.agent2d.intercept with librcsc (via ./harness) on random goalie states."""
import math, os, random, subprocess, sys
# this checkout's package (tools/librcsc_intercept_harness/ -> envs/)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'envs'))
HARNESS = os.environ.get('HARNESS', os.path.join(os.path.dirname(os.path.abspath(__file__)), 'harness'))
from hfo2d.agent2d.common import GoalieView
from hfo2d.agent2d.intercept import build_intercept_table

def gen(rng):
    px = rng.uniform(-52.5, -30); py = rng.uniform(-15, 15)
    sp = rng.choice([0.0, 0.0, rng.uniform(0, 1.0)]); a = rng.uniform(-180, 180)
    vx, vy = sp*math.cos(math.radians(a)), sp*math.sin(math.radians(a))
    d = rng.choice([rng.uniform(0.5, 4), rng.uniform(0, 12), rng.uniform(0, 40)]); ba = rng.uniform(-180, 180)
    bx, by = px + d*math.cos(math.radians(ba)), py + d*math.sin(math.radians(ba))
    bs = rng.choice([0.0, rng.uniform(0, 0.8), rng.uniform(0, 3.0)]); wa = rng.uniform(-180, 180)
    wx, wy = bs*math.cos(math.radians(wa)), bs*math.sin(math.radians(wa))
    st = rng.choice([8000.0, 8000.0, rng.uniform(2000, 8000), rng.uniform(2300, 3500), rng.uniform(0, 2600)])
    ef = rng.choice([1.0, 1.0, rng.uniform(0.6, 1.0)]); rec = rng.choice([1.0, 1.0, rng.uniform(0.5, 1.0)])
    kick_opp = rng.random() < 0.3
    has_opp = rng.random() < 0.9
    return GoalieView(cycle=0, px=px, py=py, vx=vx, vy=vy, body=rng.uniform(-180, 180), stamina=st, effort=ef,
                      recovery=rec, bx=bx, by=by, wx=0.0 if kick_opp else wx, wy=0.0 if kick_opp else wy,
                      true_wx=wx, true_wy=wy, has_opp=has_opp, ox=bx + rng.uniform(-5, 5),
                      oy=by + rng.uniform(-5, 5), ux=rng.uniform(-0.5, 0.5), uy=rng.uniform(-0.5, 0.5),
                      obody=rng.uniform(-180, 180), opp_tackle_count=rng.choice([0]*8 + [1, 3, 9]),
                      kick_opp=kick_opp, self_kickable=math.hypot(bx - px, by - py) <= 1.03,
                      lk_not_ours=rng.random() < 0.9)

def line(v):
    f = [v.px, v.py, v.vx, v.vy, v.body, v.stamina, v.effort, v.recovery, v.bx, v.by, v.wx, v.wy]
    s = ' '.join(repr(x) for x in f)
    s += f' {int(v.has_opp)} {v.ox!r} {v.oy!r} {v.ux!r} {v.uy!r} {v.obody!r} {v.opp_tackle_count}'
    s += f' {int(v.kick_opp)} {int(v.self_kickable)} {int(v.lk_not_ours)}'
    return s

def run(views, pr, br):
    out = subprocess.run([HARNESS, repr(pr), repr(br)], input='\n'.join(line(v) for v in views) + '\n',
                         capture_output=True, text=True, check=True).stdout.split('\n')
    res = []; i = 0
    while i < len(out) and out[i].startswith('T'):
        _, sm, om, n, nc = out[i].split(); n = int(n); ents = []
        for j in range(n):
            p = out[i + 1 + j].split()
            ents.append((int(p[1]), int(p[2]), int(p[3])) + tuple(float(x) for x in p[4:]))
        res.append((int(sm), int(om), int(nc), ents)); i += 1 + n
    return res

def ours(v, pr, br):
    t = build_intercept_table(v, pr, br)
    ents = [(e.mode, e.turn_cycle, e.dash_cycle, e.dash_power, e.dash_dir, e.self_x, e.self_y, e.ball_dist, e.stamina)
            for e in t.self_cache]
    return (t.self_min, t.opp_min, len(t.ball_cache), ents)

def ours_fast(v, pr, br):
    """The goalie's fast (full=False, lazy) table: only self_min, opp_min and the first entry are librcsc's."""
    t = build_intercept_table(v, pr, br, full=False)
    e = t.self_cache[:1]
    ents = [(x.mode, x.turn_cycle, x.dash_cycle, x.dash_power, x.dash_dir, x.self_x, x.self_y, x.ball_dist, x.stamina)
            for x in e]
    return (t.self_min, t.opp_min, len(t.ball_cache), ents)

def main():
    seed = int(sys.argv[1]); n = int(sys.argv[2])
    rng = random.Random(seed)
    bad = 0; bad_fast = 0; total = 0; counts = {}
    for pr, br in ((0.1, 0.05), (0.0, 0.0)):
        views = [gen(rng) for _ in range(n)]
        ref = run(views, pr, br)
        assert len(ref) == len(views)
        for v, r in zip(views, ref):
            o = ours(v, pr, br); total += 1
            if ours_fast(v, pr, br) != r[:3] + (r[3][:1],):
                bad_fast += 1
            for e in r[3]:
                k = ('EXH' if e[0] else 'NOR', 'turn' if e[1] else 'noturn', min(e[1] + e[2], 7), e[3] < 0)
                counts[k] = counts.get(k, 0) + 1
            if o != r:
                bad += 1
                if bad <= 4:
                    print('MISMATCH', pr, br, v)
                    print('  lib', r[:3]); [print('   ', e) for e in r[3]]
                    print('  py ', o[:3]); [print('   ', e) for e in o[3]]
    print('states', total, 'mismatches', bad, 'fast-table mismatches', bad_fast)
    print('entry kinds seen:', len(counts), 'EXHAUST entries:', sum(c for k, c in counts.items() if k[0] == 'EXH'),
          'back-dash entries:', sum(c for k, c in counts.items() if k[3]))

if __name__ == '__main__':
    main()
