#!/usr/bin/python3
"""Strings against cpfg: does `graftal derive` give the string cpfg gives, model by model?

Usage: scripts/cpfg_string_survey.py CPFG MODELS_DIR [--graftal build/graftal]
                                     [--markdown OUT.md] [--timeout SECONDS] [--seeds N]
       scripts/cpfg_string_survey.py --self-test   (checks the comparison rule alone)

CPFG is the user's own cpfg binary (graftal ships none: cpfg is GPL-3 and is not part of
graftal).  It is run in batch mode exactly as the cpfg oracle pack was made:
`cpfg -g -m MAP -str OUT NAME.l VIEW`, from the model's folder, with the folder's .map (or a
grey ramp) and its .v (or an empty view file).  graftal is run as `graftal derive FOLDER`.

Every folder under MODELS_DIR that holds one .l file is one model.  Strings are compared with
the oracle's rule (../shared/cpfg-oracle/check.sh): newlines removed, split into modules (one
symbol and an optional parenthesised parameter list), symbols and parameter counts equal,
parameters within a relative 1e-4 (absolute floor 1e-6).

Stochastic models (a `seed:` line, or ran/nran/bran/biran in the file) cannot give cpfg's
string: the random streams differ.  When their strings differ they are compared by statistics
instead: graftal derives the model with seeds 1..N (--seeds, default 10); the model agrees when
both strings use the same set of symbols and cpfg's module count lies within graftal's
smallest and largest count widened by 10 %.

A cpfg build may say on standard error that it lacks a feature the model needs (a line that
starts with `cpfg-batch:`, as the instrument build described in docs/cpfg-compatibility.md
prints for query modules and func()); such models are listed as not measured.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

REL_TOL = 1e-4
ABS_FLOOR = 1e-6
NUMBER = re.compile(r'^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$')
RANDOM = re.compile(r'^\s*seed\s*:|\b(ran|nran|bran|biran)\s*\(', re.IGNORECASE | re.MULTILINE)


def modules(text):
    """The string as (symbol, parameter list or None) pairs, as check.sh splits it."""
    text = text.replace('\n', '').replace('\r', '')
    out, i = [], 0
    while i < len(text):
        symbol = text[i]
        i += 1
        params = None
        if i < len(text) and text[i] == '(':
            j = text.find(')', i + 1)
            if j < 0:
                params, i = text[i + 1:], len(text)
            else:
                params, i = text[i + 1:j], j + 1
        out.append((symbol, params))
    return out


def show(module):
    symbol, params = module
    return symbol if params is None else '%s(%s)' % (symbol, params)


def numbers_agree(a, b):
    if not NUMBER.match(a):
        return a == b
    if not NUMBER.match(b):
        return False
    x, y = float(a), float(b)
    d = abs(x - y)
    return d <= ABS_FLOOR or d <= REL_TOL * max(abs(x), abs(y))


def first_difference(expected, actual):
    """'' when the strings agree, else where and how they first differ."""
    for k, (e, a) in enumerate(zip(expected, actual)):
        bad = e[0] != a[0] or (e[1] is None) != (a[1] is None)
        if not bad and e[1] is not None:
            ev, av = e[1].split(','), a[1].split(',')
            bad = len(ev) != len(av) or not all(numbers_agree(x, y) for x, y in zip(ev, av))
        if bad:
            return 'module %d: cpfg %s, graftal %s' % (k + 1, show(e), show(a))
    if len(expected) != len(actual):
        k = min(len(expected), len(actual))
        extra = ('cpfg has %s' % show(expected[k]) if len(expected) > k
                 else 'graftal has %s' % show(actual[k]))
        return '%d modules from cpfg, %d from graftal (first extra at module %d: %s)' % (
            len(expected), len(actual), k + 1, extra)
    return ''


def run(cmd, timeout, cwd=None):
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=cwd)
        return p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        return 'timeout', '', 'timeout after %d s' % timeout


def model_files(folder):
    names = sorted(os.listdir(folder))
    lfiles = [n for n in names if n.endswith('.l')]
    views = [n for n in names if n.endswith('.v')]
    maps = [n for n in names if n.endswith('.map')]
    return lfiles, views, maps


def cpfg_string(cpfg, folder, scratch, timeout):
    """(string or None, message) from the user's cpfg run in batch mode in the model's folder."""
    lfiles, views, maps = model_files(folder)
    view = os.path.abspath(os.path.join(folder, views[0])) if views else os.path.join(scratch, 'empty.v')
    colours = os.path.abspath(os.path.join(folder, maps[0])) if maps else os.path.join(scratch, 'grey.map')
    out = os.path.join(scratch, 'cpfg.str')
    if os.path.exists(out):
        os.remove(out)
    code, _, err = run([cpfg, '-g', '-m', colours, '-str', out, lfiles[0], view], timeout,
                       cwd=folder)
    lacks = [line.split(':', 1)[1].strip() for line in err.splitlines()
             if line.startswith('cpfg-batch:')]
    if not os.path.exists(out) or os.path.getsize(out) == 0:
        last = [line for line in err.splitlines() if line.strip()]
        return None, 'cpfg wrote no string (%s)' % (last[-1].strip() if last else 'exit %s' % code), lacks
    with open(out) as f:
        return f.read(), '', lacks


def graftal_string(graftal, folder, timeout, seed=None):
    cmd = [graftal, 'derive', '--quiet', '--threads', '1', folder]
    if seed is not None:
        cmd[2:2] = ['--seed', str(seed)]
    code, out, err = run(cmd, timeout)
    if code != 0:
        lines = [line for line in err.splitlines() if line.strip()]
        return None, (lines[0].strip() if lines else 'exit %s' % code)[:200]
    return out, ''


def statistics_agree(cpfg_modules, graftal, folder, timeout, seeds):
    counts, symbols = [], set()
    for seed in range(1, seeds + 1):
        text, err = graftal_string(graftal, folder, timeout, seed)
        if text is None:
            return False, 'graftal failed with seed %d: %s' % (seed, err)
        ms = modules(text)
        counts.append(len(ms))
        symbols |= {m[0] for m in ms}
    cpfg_symbols = {m[0] for m in cpfg_modules}
    low, high = 0.9 * min(counts), 1.1 * max(counts)
    n = len(cpfg_modules)
    detail = 'cpfg %d modules; graftal %d..%d over seeds 1..%d' % (n, min(counts), max(counts), seeds)
    if cpfg_symbols != symbols:
        only_cpfg = ''.join(sorted(cpfg_symbols - symbols))
        only_graftal = ''.join(sorted(symbols - cpfg_symbols))
        return False, detail + '; symbols only in cpfg: %r, only in graftal: %r' % (only_cpfg, only_graftal)
    return low <= n <= high, detail


def survey(cpfg, root, graftal, timeout, seeds):
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        open(os.path.join(scratch, 'empty.v'), 'w').close()
        with open(os.path.join(scratch, 'grey.map'), 'wb') as f:
            f.write(bytes(v for i in range(256) for v in (i, i, i)))
        for dirpath, dirnames, filenames in sorted(os.walk(root)):
            dirnames.sort()
            lfiles = [n for n in filenames if n.endswith('.l')]
            if len(lfiles) != 1:
                continue
            name = os.path.relpath(dirpath, root)
            with open(os.path.join(dirpath, lfiles[0]), errors='replace') as f:
                stochastic = bool(RANDOM.search(f.read()))
            row = {'model': name, 'stochastic': stochastic}
            expected, why, lacks = cpfg_string(cpfg, dirpath, scratch, timeout)
            if lacks:
                row.update(result='not measured', detail='cpfg build lacks: ' + '; '.join(lacks))
            elif expected is None:
                row.update(result='cpfg: no string', detail=why)
            else:
                actual, err = graftal_string(graftal, dirpath, timeout)
                if actual is None:
                    row.update(result='graftal error', detail=err)
                else:
                    e, a = modules(expected), modules(actual)
                    diff = first_difference(e, a)
                    if not diff:
                        row.update(result='equal', detail='%d modules' % len(e))
                    elif stochastic:
                        ok, detail = statistics_agree(e, graftal, dirpath, timeout, seeds)
                        row.update(result='statistics agree' if ok else 'statistics differ',
                                   detail=detail)
                    else:
                        row.update(result='differ', detail=diff)
            rows.append(row)
    return rows


def table(rows, cpfg):
    lines = ['cpfg: %s (the user\'s own build; graftal ships no cpfg)' % cpfg, '',
             '| model | stochastic | result | detail |', '| --- | --- | --- | --- |']
    for r in rows:
        detail = r['detail'].replace('|', '\\|')
        lines.append('| %s | %s | %s | %s |' % (r['model'], 'yes' if r['stochastic'] else '',
                                                r['result'], detail))
    runs = [r for r in rows if r['result'] not in ('cpfg: no string', 'not measured')]
    good = [r for r in runs if r['result'] in ('equal', 'statistics agree')]
    lines.append('')
    lines.append('%d of %d models that cpfg runs give cpfg\'s string (or, stochastic, its statistics); '
                 '%d not measured, %d rejected by cpfg.' % (
                     len(good), len(runs), sum(r['result'] == 'not measured' for r in rows),
                     sum(r['result'] == 'cpfg: no string' for r in rows)))
    return '\n'.join(lines)


def self_test():
    """The comparison rule on strings whose answer is known; exits non-zero on a wrong one."""
    cases = [
        ('F(1)+F(2)', 'F(1)\n+F(2)', ''),  # line breaks do not count
        ('F(6.12323e-17)', 'F(0)', ''),  # absolute floor
        ('F(100000)', 'F(100004)', ''),  # within 1e-4 relative
        ('F(100000)', 'F(100020)', 'module 1: cpfg F(100000), graftal F(100020)'),
        ('F(1,2)', 'F(1)', 'module 1: cpfg F(1,2), graftal F(1)'),
        ('AB', 'AC', 'module 2: cpfg B, graftal C'),
        ('A', 'A(0)', 'module 1: cpfg A, graftal A(0)'),
        ('AB', 'A', '2 modules from cpfg, 1 from graftal (first extra at module 2: cpfg has B)'),
    ]
    wrong = 0
    for expected, actual, answer in cases:
        got = first_difference(modules(expected), modules(actual))
        if got != answer:
            wrong += 1
            print('self-test: %r against %r gave %r, expected %r' % (expected, actual, got, answer))
    print('%d passed, %d failed' % (len(cases) - wrong, wrong))
    sys.exit(1 if wrong else 0)


def main():
    if sys.argv[1:] == ['--self-test']:
        self_test()
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('cpfg', help="the user's own cpfg binary")
    parser.add_argument('models')
    parser.add_argument('--graftal', default=os.path.join(os.path.dirname(__file__), '..', 'build', 'graftal'))
    parser.add_argument('--markdown')
    parser.add_argument('--timeout', type=int, default=120)
    parser.add_argument('--seeds', type=int, default=10)
    args = parser.parse_args()
    for path in (args.cpfg, args.graftal):
        if not os.access(path, os.X_OK):
            sys.exit('cpfg_string_survey: %s is not an executable file' % path)
    text = table(survey(os.path.abspath(args.cpfg), args.models, os.path.abspath(args.graftal),
                        args.timeout, args.seeds), args.cpfg)
    print(text)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(text + '\n')


if __name__ == '__main__':
    main()
