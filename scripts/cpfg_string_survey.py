#!/usr/bin/python3
"""Strings against cpfg: does `graftal derive` give the string cpfg gives, model by model?

Usage: scripts/cpfg_string_survey.py CPFG MODELS_DIR [--graftal build/graftal]
                                     [--markdown OUT.md] [--timeout SECONDS]
       scripts/cpfg_string_survey.py --self-test   (checks the comparison rule alone)

CPFG is the user's own cpfg binary (graftal ships none: cpfg is GPL-3 and is not part of
graftal), with vlabcpp on the PATH.  MODELS_DIR is a tree of vlab model folders (vlab's
`oofs/ext`, say).

The models: every cpfg command in a folder's vlab `specifications` file (`cpfg -M plant.mat
plant.l plant.v plant.a`) is one model, its .l and view file as the command names them
(lpfg's models are left out: their command is lpfg); a folder without a specifications file
and with one .l file is one model too, with its one .v.  cpfg is run in batch mode as the
cpfg oracle pack was made, `cpfg -g -m MAP|-M MATERIALS -str OUT NAME.l VIEW`, from the
model's folder, with the command's colour map or materials (or a grey ramp).  graftal is
run as `graftal derive FOLDER` for a folder's first command (which picks the files from the
specifications) and `graftal derive NAME.l VIEW` for the others.  A model read with a view
file draws cpfg's random numbers in graftal, so stochastic models are compared string for
string like the others.

Strings are compared with the oracle's rule (../shared/cpfg-oracle/check.sh): newlines
removed, split into modules (one symbol and an optional parenthesised parameter list),
symbols and parameter counts equal, parameters within a relative 1e-4 (absolute floor 1e-6).
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


def cpfg_commands(folder):
    """The cpfg commands of the folder's specifications, as dicts of the files they name."""
    path = os.path.join(folder, 'specifications')
    if not os.path.exists(path):
        return None
    with open(path, errors='replace') as f:
        lines = f.read().splitlines()
    commands = []
    for line in lines:
        words = line.split()
        if not words or os.path.basename(words[0]) != 'cpfg':
            continue
        cmd, k = {'l': None, 'v': None, 'map': None, 'mat': None}, 1
        while k < len(words):
            w = words[k]
            if w in ('-w', '-wr', '-wp', '-wpr'):
                k += 3
                continue
            if w in ('-m', '-m1', '-m2', '-M', '-e', '-P', '-str'):
                if w in ('-m', '-m1') and k + 1 < len(words) and cmd['map'] is None:
                    cmd['map'] = words[k + 1]
                if w == '-M' and k + 1 < len(words):
                    cmd['mat'] = words[k + 1]
                k += 2
                continue
            if w.endswith('.l') and cmd['l'] is None:
                cmd['l'] = w
            elif w.endswith('.v') and cmd['v'] is None:
                cmd['v'] = w
            k += 1
        if cmd['l'] and os.path.exists(os.path.join(folder, cmd['l'])) and \
                all(c['l'] != cmd['l'] for c in commands):
            commands.append(cmd)
    return commands


def models_of(folder, filenames):
    """The models of a folder: its specifications' cpfg commands, else its one .l."""
    commands = cpfg_commands(folder)
    if commands is not None:
        return commands
    lfiles = sorted(n for n in filenames if n.endswith('.l'))
    if len(lfiles) != 1:
        return []
    views = sorted(n for n in filenames if n.endswith('.v'))
    maps = sorted(n for n in filenames if n.endswith('.map'))
    return [{'l': lfiles[0], 'v': views[0] if len(views) == 1 else None,
             'map': maps[0] if len(maps) == 1 else None, 'mat': None}]


def cpfg_string(cpfg, folder, model, scratch, timeout):
    """(string or None, message) from the user's cpfg run in batch mode in the model's folder."""
    view = model['v'] if model['v'] and os.path.exists(os.path.join(folder, model['v'])) else None
    view = os.path.abspath(os.path.join(folder, view)) if view else os.path.join(scratch, 'empty.v')
    colours = ['-m', os.path.join(scratch, 'grey.map')]
    if model['mat'] and os.path.exists(os.path.join(folder, model['mat'])):
        colours = ['-M', model['mat']]
    elif model['map'] and os.path.exists(os.path.join(folder, model['map'])):
        colours = ['-m', model['map']]
    out = os.path.join(scratch, 'cpfg.str')
    if os.path.exists(out):
        os.remove(out)
    code, _, err = run([cpfg, '-g'] + colours + ['-str', out, model['l'], view], timeout,
                       cwd=folder)
    if not os.path.exists(out) or os.path.getsize(out) == 0:
        last = [line for line in err.splitlines() if line.strip()]
        return None, 'cpfg wrote no string (%s)' % (last[-1].strip()[:120] if last else 'exit %s' % code)
    with open(out) as f:
        return f.read(), ''


def graftal_string(graftal, args, timeout):
    code, out, err = run([graftal, 'derive', '--quiet', '--threads', '1'] + args, timeout)
    if code != 0:
        lines = [line for line in err.splitlines() if line.strip()]
        return None, (lines[0].strip() if lines else 'exit %s' % code)[:200]
    return out, ''


def survey(cpfg, root, graftal, timeout):
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        open(os.path.join(scratch, 'empty.v'), 'w').close()
        with open(os.path.join(scratch, 'grey.map'), 'wb') as f:
            f.write(bytes(v for i in range(256) for v in (i, i, i)))
        for dirpath, dirnames, filenames in sorted(os.walk(root)):
            dirnames.sort()
            models = models_of(dirpath, filenames)
            for index, model in enumerate(models):
                name = os.path.relpath(dirpath, root)
                if len(models) > 1:
                    name += ' (%s)' % model['l']
                with open(os.path.join(dirpath, model['l']), errors='replace') as f:
                    stochastic = bool(RANDOM.search(f.read()))
                row = {'model': name, 'stochastic': stochastic}
                expected, why = cpfg_string(cpfg, dirpath, model, scratch, timeout)
                if expected is None:
                    row.update(result='cpfg: no string', detail=why)
                    rows.append(row)
                    continue
                if index == 0:
                    args = [dirpath]
                else:
                    args = [os.path.join(dirpath, model['l'])]
                    if model['v'] and os.path.exists(os.path.join(dirpath, model['v'])):
                        args.append(os.path.join(dirpath, model['v']))
                actual, err = graftal_string(graftal, args, timeout)
                if actual is None:
                    row.update(result='graftal error', detail=err)
                else:
                    e, a = modules(expected), modules(actual)
                    diff = first_difference(e, a)
                    if not diff:
                        row.update(result='equal', detail='%d modules' % len(e))
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
    runs = [r for r in rows if r['result'] != 'cpfg: no string']
    good = [r for r in runs if r['result'] == 'equal']
    lines.append('')
    lines.append('%d of %d models give cpfg\'s string (%d of the %d stochastic ones); '
                 'cpfg wrote no string for %d of the %d models.' % (
                     len(good), len(runs), sum(r['stochastic'] for r in good),
                     sum(r['stochastic'] for r in runs),
                     sum(r['result'] == 'cpfg: no string' for r in rows), len(rows)))
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
    args = parser.parse_args()
    for path in (args.cpfg, args.graftal):
        if not os.access(path, os.X_OK):
            sys.exit('cpfg_string_survey: %s is not an executable file' % path)
    text = table(survey(os.path.abspath(args.cpfg), args.models, os.path.abspath(args.graftal),
                        args.timeout), args.cpfg)
    print(text)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(text + '\n')


if __name__ == '__main__':
    main()
