#!/usr/bin/python3
"""scripts/bench-vs-smac --report on synthetic result files (no Smac needed): with --repeat each
query's time is the median of its runs before the median over queries is taken, a figure that
most runs did not reach counts as not reached, and a one-run file reports as it did.

  bench_vs_smac_report_test.py SOURCE_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(sys.argv[1], 'scripts', 'bench-vs-smac')


def ours(first_s, proof_s, cost=1000, proven=True, rss=40.0):
    """One `amha plan` run: a first path of cost * 1.02 at first_s, the optimum `cost` at proof_s."""
    sols = [{'cost': int(cost * 1.02), 'elapsed_s': first_s}]
    if proof_s is not None:
        sols.append({'cost': cost, 'elapsed_s': proof_s})
    return {'heuristic_seconds': 0.0, 'elapsed_s': proof_s or first_s, 'solutions': sols,
            'status': 'proven_optimal' if proven and proof_s is not None else 'time_limit', 'rss_mb': rss}


def smac(plan_s, rss=30.0):
    return {'ok': True, 'plan_s': plan_s, 'setup_s': 0.5, 'rss_mb': rss}


def row(i, smac_runs, our_runs):
    r = {'query': i, 'start': '0,0,0', 'goal': '1,1,0', 'optimum': {'smac': 1000},
         'smac': smac_runs[0], 'ours': {'smac': our_runs[0]}}
    if len(smac_runs) > 1:
        r['repeats'] = [{'smac': s, 'ours': {'smac': o}} for s, o in zip(smac_runs[1:], our_runs[1:])]
    return r


def report(rows):
    with tempfile.NamedTemporaryFile('w', suffix='.json', delete=False) as f:
        json.dump({'command': 'test', 'rows': rows}, f)
    try:
        return subprocess.run([SCRIPT, '--report', f.name], capture_output=True, text=True, check=True).stdout
    finally:
        os.unlink(f.name)


def line(out, prefix):
    got = [l for l in out.splitlines() if l.startswith(prefix)]
    assert len(got) == 1, out
    return got[0]


failures = []


def expect(what, text, wanted):
    if wanted not in text:
        failures.append('%s: %r not in %r' % (what, wanted, text))


# Query 0: Smac 0.10, 0.30, 0.11 s (median 0.11); our proofs 0.50, 0.20, 0.22 s (median 0.22: x2.00;
# the first round alone would say x5.00). Query 1: Smac 0.20 s each time; our proof 0.40 s in two of
# three runs, not proven in one (median 0.40: x2.00). Over the queries: proof x2.00, 0.310 s.
three = report([
    row(0, [smac(0.10), smac(0.30), smac(0.11)], [ours(0.01, 0.50), ours(0.02, 0.20), ours(0.03, 0.22)]),
    row(1, [smac(0.20)] * 3, [ours(0.05, 0.40), ours(0.05, None), ours(0.05, 0.40)]),
])
smac_line = line(three, '| Smac Lattice')
expect('Smac median of per-query medians (0.11, 0.20)', smac_line, '| 0.155 s (setup 0.500 s)')
ours_line = line(three, '| ours, smac set')
expect('proof: per-query medians 0.22 and 0.40', ours_line, '| 0.310 s (x2.00), 2 |')
expect('first: per-query medians 0.02 and 0.05, ratios 0.18 and 0.25', ours_line, '| 0.035 s (x0.22) |')

# A figure reached in one run of three is not reached: query 1's proof is then not counted.
once = report([
    row(0, [smac(0.10)] * 3, [ours(0.01, 0.30)] * 3),
    row(1, [smac(0.20)] * 3, [ours(0.05, None), ours(0.05, 0.40), ours(0.05, None)]),
])
expect('a proof in 1 of 3 runs is no proof', line(once, '| ours, smac set'), '| 0.300 s (x3.00), 1 |')

# One run per query (result files written before --repeat): the first round's figures.
single = report([row(0, [smac(0.10)], [ours(0.01, 0.50)]), row(1, [smac(0.20)], [ours(0.05, 0.40)])])
expect('one run per query', line(single, '| ours, smac set'), '| 0.450 s (x3.50), 2 |')

if failures:
    print('\n'.join(failures))
    sys.exit(1)
print('bench-vs-smac --report: medians of repeated runs as expected')
