#!/usr/bin/env python3
"""A reference environment program for graftal's `process` environment (python3 stdlib only).

The line protocol (docs/environments.md has it in full). For every derivation step whose
string has ?E modules graftal writes

    step N COUNT

followed by COUNT request lines, one per ?E module in string order,

    INDEX X Y Z HX HY HZ LX LY LZ UX UY UZ P1 ... Pn

(the module's position in the string, the turtle's position, heading, left and up vectors,
then the module's n parameters), and reads back COUNT answer lines of exactly n numbers
each, one per parameter. End of input means the derivation is over.

This program is a height field, y = BASE + AMPLITUDE * sin(360 deg * x / WAVELENGTH): a
ceiling over the plants. It answers each ?E with

    P1 = clearance: the height of the field above the module (negative above the field)
    P2 = the height of the field at the module's x

and sends any further parameters back unchanged.

Usage: height_field.py [BASE [AMPLITUDE [WAVELENGTH]]]     (defaults: 6 0 12)
"""
import math
import sys


def main():
    args = [float(a) for a in sys.argv[1:4]]
    base, amplitude, wavelength = args + [6.0, 0.0, 12.0][len(args):]
    for header in sys.stdin:
        words = header.split()
        if len(words) != 3 or words[0] != "step":
            sys.exit("height_field.py: expected 'step N COUNT', got %r" % header)
        answers = []
        for _ in range(int(words[2])):
            fields = sys.stdin.readline().split()
            if len(fields) < 13:
                sys.exit("height_field.py: a request line has fewer than 13 fields")
            x, y = float(fields[1]), float(fields[2])
            params = fields[13:]
            height = base + amplitude * math.sin(2 * math.pi * x / wavelength)
            values = [repr(height - y), repr(height)] + params[2:]
            answers.append(" ".join(values[: len(params)]))
        # Answers must be flushed: graftal waits for them before the next step.
        sys.stdout.write("".join(a + "\n" for a in answers))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
