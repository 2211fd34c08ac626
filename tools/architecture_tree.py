#!/usr/bin/env python3
"""Print the tree of mech-core/src for ARCHITECTURE.md: one line per file, its path and the
first sentence of its `//!` doc. `--write` replaces the first ```text block of
ARCHITECTURE.md with it (the test `architecture_draws_the_tree_on_disk` in
mech-core/tests/imports.rs checks the block against the disk)."""
import os, re, sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
LAYERS = ['lib.rs', 'private.rs', 'error.rs', 'kernel', 'elements', 'model', 'front', 'plan',
          'checks', 'solvers', 'spatial', 'dynamics', 'strength', 'runtime', 'design']

def summary(path):
    doc = []
    for line in open(path, encoding='utf-8'):
        if line.startswith('//!'):
            doc.append(line[3:].strip())
        elif doc or line.strip():
            break
    text = ' '.join(doc)
    text = re.sub(r'\[`([^`]*)`\]\([^)]*\)', r'\1', text)
    text = re.sub(r'\[`([^`]*)`\]', r'\1', text).replace('`', '')
    s = text
    for m in re.finditer(r'[.:;](\s|$)', text):
        head = text[:m.start()]
        if head.count('(') == head.count(')'):
            s = head
            break
    return s if len(s) <= 90 else s[:87].rsplit(' ', 1)[0] + ' …'

def files():
    src = os.path.join(ROOT, 'mech-core', 'src')
    out = []
    for top in LAYERS:
        p = os.path.join(src, top)
        if os.path.isdir(p):
            for dp, dns, fns in sorted(os.walk(p)):
                dns.sort()
                for f in sorted(fns, key=lambda f: (f != 'mod.rs', f)):
                    if f.endswith('.rs'):
                        out.append(os.path.join(dp, f))
        elif os.path.exists(p):
            out.append(p)
    rest = {os.path.join(dp, f) for dp, _, fns in os.walk(src) for f in fns if f.endswith('.rs')}
    missing = rest - set(out)
    if missing:
        sys.exit(f'files outside the known layers: {sorted(missing)}')
    return out

def block():
    rows = [(os.path.relpath(p, ROOT), summary(p)) for p in files()]
    w = max(len(r[0]) for r in rows) + 2
    return '\n'.join(f'{p:<{w}}{s}'.rstrip() for p, s in rows) + '\n'

if __name__ == '__main__':
    b = block()
    if '--write' in sys.argv:
        path = os.path.join(ROOT, 'ARCHITECTURE.md')
        t = open(path, encoding='utf-8').read()
        i = t.index('```text\n') + len('```text\n')
        j = t.index('```', i)
        open(path, 'w', encoding='utf-8').write(t[:i] + b + t[j:])
    else:
        sys.stdout.write(b)
