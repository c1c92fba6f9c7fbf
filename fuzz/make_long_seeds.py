#!/usr/bin/env python3
"""Writes long seed inputs (up to 1 MB) for fuzz_parser into the directory given: the hostile
shapes a parser must refuse quickly. The first byte selects the parser (see parser_fuzz.cpp):
'c' (0 mod 3) infix, 'a' (1 mod 3) S-expression, 'b' (2 mod 3) a whole features file."""
import os
import sys

MB = 1 << 20
seeds = {
    "infix-chain": "c" + "+".join(["x"] * 200000),
    "infix-product": "c" + "*".join(["a"] * 300000),
    "infix-nesting": "c" + "(" * (MB // 2) + "x" + ")" * (MB // 2 - 2),
    "infix-negations": "c" + "-" * (MB - 2) + "x",
    "infix-calls": "c" + "sin(" * (MB // 8) + "x" + ")" * (MB // 8),
    "infix-arguments": "c" + "max(" + ",".join(["x"] * 200000) + ")",
    "infix-number": "c" + "1" * (MB - 1),
    "infix-identifier": "c" + "a" * (MB - 1),
    "infix-spaces": "c" + " " * (MB - 2) + "x",
    "sexpr-flat": "a(+ " + " ".join(["x"] * 300000) + ")",
    "sexpr-nesting": "a" + "(sin " * (MB // 5) + "x" + ")" * (MB // 5),
    "file-lines": "b# variables: a, b, x\n" + "a + b * x\n" * 100000,
    "file-comments": "b" + "# k: v\n" * 140000 + "x\n",
}
out = sys.argv[1]
os.makedirs(out, exist_ok=True)
for name, text in seeds.items():
    with open(os.path.join(out, name), "w") as f:
        f.write(text[:MB])
