#!/usr/bin/python3
"""Survey of cpfg model folders: does graftal derive and draw each one?

Usage: scripts/cpfg_survey.py MODELS_DIR [--graftal build/graftal] [--markdown OUT.md]
                              [--timeout SECONDS] [--self-test]

Every folder under MODELS_DIR that holds a `.l` file is one model, given to graftal as a
model folder (its one `.l`, its one `.v`, the files they name).  For each, the survey runs
`graftal stats FOLDER` (derives) and `graftal render FOLDER -o picture.png` (draws), and
records: derived without error, rendered a picture that is not blank (at least 0.2 % of
its pixels differ from the background), the first error line, the first warning line.  The table goes to standard output
(and, with --markdown, to a file) with the counts and the errors grouped by their message.

The models themselves are not part of graftal (vlab's are GPL-3): fetch them into a folder
of your own.  The survey cannot say whether the strings equal cpfg's: cpfg is not run here.
"""
import argparse
import collections
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib


def png_ink(path):
    """The share of the PNG's pixels that differ from its top-left pixel (the background)."""
    with open(path, 'rb') as f:
        data = f.read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        return 0.0
    pos, idat, width, height, depth, ctype = 8, b'', 0, 0, 8, 2
    while pos < len(data):
        (length,) = struct.unpack('>I', data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        if kind == b'IHDR':
            width, height, depth, ctype = struct.unpack('>IIBB', body[:10])
        elif kind == b'IDAT':
            idat += body
        pos += 12 + length
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[ctype]
    bpp = max(1, channels * depth // 8)
    stride = (width * channels * depth + 7) // 8
    raw = zlib.decompress(idat)
    background = None
    inked = 0
    prev = bytearray(stride)
    for row in range(height):
        start = row * (stride + 1)
        kind = raw[start]
        line = bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            left = line[i - bpp] if i >= bpp else 0
            up = prev[i]
            upleft = prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + ((left + up) >> 1)) & 255
            elif kind == 4:
                p = left + up - upleft
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - upleft)
                pred = left if pa <= pb and pa <= pc else (up if pb <= pc else upleft)
                line[i] = (line[i] + pred) & 255
        prev = line
        for i in range(0, len(line), bpp):
            pixel = bytes(line[i:i + bpp])
            if background is None:
                background = pixel
            elif pixel != background:
                inked += 1
    return inked / max(1, width * height)


# A picture counts as drawn when at least this share of its pixels is not background: a
# few pixels in the middle (a plant drawn at a hundredth of its size) is not a picture.
MIN_INK = 0.002


def first_line(text, pattern):
    for line in text.splitlines():
        if re.search(pattern, line):
            return line.strip()
    return ''


def run(cmd, timeout):
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        return p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        return 'timeout', 'timeout after %d s' % timeout


def survey_model(folder, graftal, timeout, scratch):
    row = {'model': folder}
    code, err = run([graftal, 'stats', '--threads', '1', folder], timeout)
    row['derives'] = code == 0
    row['error'] = '' if code == 0 else (first_line(err, r'error') or err.strip()[:200]
                                         or 'exit %s' % code)
    row['warning'] = first_line(err, r'warning')
    picture = os.path.join(scratch, 'picture.png')
    if os.path.exists(picture):
        os.remove(picture)
    row['renders'] = False
    if row['derives']:
        code, err = run([graftal, 'render', '--threads', '1', '--size', '200x200', folder,
                         '-o', picture], timeout)
        if code == 0 and os.path.exists(picture):
            ink = png_ink(picture)
            row['renders'] = ink >= MIN_INK
            if not row['renders']:
                row['error'] = 'blank picture' if ink == 0 else 'almost blank picture (%.2f %% drawn)' % (100 * ink)
        else:
            row['error'] = first_line(err, r'error') or err.strip()[:200] or 'exit %s' % code
    return row


def model_folders(root):
    found = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        if any(name.endswith('.l') for name in filenames):
            found.append(dirpath)
    return found


def error_kind(message):
    """The message without its file:line:column, so that equal causes group together."""
    message = re.sub(r' [(][0-9.]+ % drawn[)]', '', message)
    return re.sub(r'^[^ ]*:[0-9]+(:[0-9]+)?: ', '', message)[:120]


def table(rows, root):
    out = []
    derived = sum(r['derives'] for r in rows)
    drawn = sum(r['renders'] for r in rows)
    out.append('%d models: %d derive without error, %d render a non-blank picture'
               % (len(rows), derived, drawn))
    out.append('')
    out.append('| model | derives | renders | first error |')
    out.append('| --- | --- | --- | --- |')
    for r in rows:
        name = os.path.relpath(r['model'], root)
        error = r['error'].replace('|', '\\|').replace(root + '/', '')
        out.append('| %s | %s | %s | %s |' % (name, 'yes' if r['derives'] else 'no',
                                             'yes' if r['renders'] else 'no', error))
    kinds = collections.Counter(error_kind(r['error'].replace(root + '/', ''))
                                for r in rows if r['error'])
    if kinds:
        out.append('')
        out.append('| failure | models |')
        out.append('| --- | --- |')
        for kind, count in kinds.most_common():
            out.append('| %s | %d |' % (kind.replace('|', '\\|'), count))
    return '\n'.join(out) + '\n'


def self_test(graftal):
    """Two made-up model folders: one draws, one is an error; the table must say so."""
    with tempfile.TemporaryDirectory() as root:
        good = os.path.join(root, 'good')
        bad = os.path.join(root, 'bad')
        os.makedirs(good)
        os.makedirs(bad)
        with open(os.path.join(good, 'plant.l'), 'w') as f:
            f.write('Lsystem: 1\nderivation length: 2\nAxiom: F\nF --> F[+F]F\nendlsystem\n')
        with open(os.path.join(good, 'plant.v'), 'w') as f:
            f.write('angle increment: 30\n')
        with open(os.path.join(bad, 'plant.l'), 'w') as f:
            f.write('Lsystem: 1\nderivation length: 2\nAxiom: F(\nendlsystem\n')
        rows = [survey_model(m, graftal, 60, root) for m in model_folders(root)]
        text = table(rows, root)
        assert '2 models: 1 derive without error, 1 render a non-blank picture' in text, text
        assert '| good | yes | yes |  |' in text, text
        assert '| bad | no | no | bad/plant.l:3:' in text, text
    print('self-test passed')


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('models', nargs='?')
    parser.add_argument('--graftal', default='build/graftal')
    parser.add_argument('--markdown')
    parser.add_argument('--timeout', type=int, default=120)
    parser.add_argument('--self-test', action='store_true')
    args = parser.parse_args()
    graftal = os.path.abspath(args.graftal)
    if args.self_test:
        self_test(graftal)
        return
    if not args.models:
        parser.error('give the folder of model folders')
    root = os.path.abspath(args.models)
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for folder in model_folders(root):
            rows.append(survey_model(folder, graftal, args.timeout, scratch))
            r = rows[-1]
            print('%-50s %-3s %-3s %s' % (os.path.relpath(folder, root),
                                          'ok' if r['derives'] else 'ERR',
                                          'ok' if r['renders'] else '--', r['error'][:100]),
                  file=sys.stderr, flush=True)
    text = table(rows, root)
    sys.stdout.write(text)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(text)


if __name__ == '__main__':
    main()
