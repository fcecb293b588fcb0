#!/usr/bin/env python3
"""Lengths of the functions and files of a C++ tree, by brace matching with
comments and string/character literals stripped (the count issue 19 names).

    scripts/function_lengths.py [--over N] [--files-over M] [DIR...]   (default: src)

Prints every function longer than N lines (default 150) and every file
longer than M lines (default 1200), longest first, then a summary line.
Exit status 0 always: it reports, it does not judge.
"""
import argparse
import os
import re
import sys

CONTROL = {'if', 'for', 'while', 'switch', 'catch', 'do', 'else', 'try', 'return'}


def strip(text):
    """Comments and literals replaced by spaces, newlines kept."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i)); i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                end = text.find(')' + m.group(1) + '"', i)
                j = n if end < 0 else end + len(m.group(1)) + 2
                out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j
            else:
                out.append(c); i += 1
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            out.append(' ' * (min(j + 1, n) - i)); i = j + 1
        else:
            out.append(c); i += 1
    return ''.join(out)


def functions(path):
    text = strip(open(path, encoding='utf-8', errors='replace').read())
    stack = []  # kinds of the open braces: 'scope' (namespace, class) or 'body'
    found = []
    for m in re.finditer(r'[{}]', text):
        if m.group() == '}':
            if stack:
                kind, start, name = stack.pop()
                if kind == 'function':
                    first = text.count('\n', 0, start) + 1
                    last = text.count('\n', 0, m.start()) + 1
                    found.append((last - first + 1, name, first))
            continue
        if any(k != 'scope' for k, _, _ in stack):
            stack.append(('body', m.start(), ''))
            continue
        head = text[max(0, m.start() - 400):m.start()]
        head = head[max(head.rfind(';'), head.rfind('}'), head.rfind('{')) + 1:]
        if re.search(r'\b(namespace|class|struct|union|enum)\b[^()]*$', head) or '=' in head.split(')')[-1]:
            stack.append(('scope', m.start(), ''))
            continue
        call = re.search(r'([~\w:<>]+)\s*\([^;]*\)\s*(const|noexcept|override|final|mutable|->[^{]*|:[^{]*|\s)*$',
                         head, re.S)
        if call and call.group(1).split('::')[-1] not in CONTROL:
            stack.append(('function', m.start(), call.group(1)))
        else:
            stack.append(('scope', m.start(), ''))
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--over', type=int, default=150)
    ap.add_argument('--files-over', type=int, default=1200)
    ap.add_argument('dirs', nargs='*', default=['src'])
    a = ap.parse_args()
    funcs, files = [], []
    for d in a.dirs:
        for root, _, names in os.walk(d):
            for name in names:
                if not name.endswith(('.cpp', '.h', '.hpp', '.cc')):
                    continue
                p = os.path.join(root, name)
                with open(p, encoding='utf-8', errors='replace') as f:
                    files.append((sum(1 for _ in f), p))
                funcs += [(n, fn, p, line) for n, fn, line in functions(p)]
    long_funcs = sorted((f for f in funcs if f[0] > a.over), reverse=True)
    long_files = sorted((f for f in files if f[0] > a.files_over), reverse=True)
    for n, fn, p, line in long_funcs:
        print(f'function {n:5d} lines  {p}:{line}  {fn}')
    for n, p in long_files:
        print(f'file     {n:5d} lines  {p}')
    lengths = sorted(f[0] for f in funcs)
    median = lengths[len(lengths) // 2] if lengths else 0
    print(f'{len(funcs)} functions (median {median} lines), {len(long_funcs)} over {a.over}; '
          f'{len(files)} files, {len(long_files)} over {a.files_over} lines')
    return 0


if __name__ == '__main__':
    sys.exit(main())
