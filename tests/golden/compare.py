#!/usr/bin/env python3
"""How far a re-blessed golden corpus moved from an earlier one, for the commit that explains it.

Usage: python3 tests/golden/compare.py OLD.jsonl NEW.jsonl
       git show REV:tests/golden/bounces.jsonl > /tmp/old.jsonl; python3 tests/golden/compare.py /tmp/old.jsonl tests/golden/bounces.jsonl

Lines are matched by their `args`. A number's move is measured against its field's scale: the largest
magnitude under the same top-level key of the old line (so a cart velocity that ends near zero is judged
against the velocities around it, not against itself). Any change of text (phase names, refusals) or of
shape (a phase more or less) is listed as a structural change. Exit status 1 when anything structural moved."""
import json
import sys


def numbers(value):
    if isinstance(value, bool):
        return
    if isinstance(value, (int, float)):
        yield float(value)
    elif isinstance(value, list):
        for v in value:
            yield from numbers(v)
    elif isinstance(value, dict):
        for v in value.values():
            yield from numbers(v)


def walk(old, new, scale, path, moves, structural):
    if isinstance(old, bool) or isinstance(new, bool) or isinstance(old, str) or isinstance(new, str):
        if old != new:
            structural.append(f"{path}: {old!r} -> {new!r}")
        return
    if isinstance(old, (int, float)) and isinstance(new, (int, float)):
        if old != new:
            moves.append((abs(old - new) / scale if scale > 0 else float("inf"), path, old, new))
        return
    if isinstance(old, list) and isinstance(new, list) and len(old) == len(new):
        for i, (a, b) in enumerate(zip(old, new)):
            walk(a, b, scale, f"{path}[{i}]", moves, structural)
        return
    if isinstance(old, dict) and isinstance(new, dict) and old.keys() == new.keys():
        for key in old:
            walk(old[key], new[key], scale, f"{path}.{key}", moves, structural)
        return
    if old != new:
        structural.append(f"{path}: {json.dumps(old)[:80]} -> {json.dumps(new)[:80]}")


def main(old_path, new_path):
    old = {json.dumps(line["args"]): line for line in map(json.loads, open(old_path))}
    new = {json.dumps(line["args"]): line for line in map(json.loads, open(new_path))}
    moved_lines, worst, structural = 0, [], []
    for key, a in old.items():
        if key not in new:
            structural.append(f"{key}: line removed")
            continue
        b = new[key]
        moves, changes = [], []
        for field in sorted(set(a) | set(b)):
            if field not in a or field not in b:
                changes.append(f"{field}: present in one corpus only")
                continue
            scale = max((abs(x) for x in numbers(a[field])), default=0.0)
            walk(a[field], b[field], scale, field, moves, changes)
        structural += [f"{key} {c}" for c in changes]
        if moves:
            moved_lines += 1
            worst.append(max(moves) + (key,))
    added = [key for key in new if key not in old]
    worst.sort(reverse=True)
    print(f"{len(old)} old lines, {len(new)} new; {moved_lines} moved, {len(added)} added, "
          f"{len(structural)} structural changes")
    if worst:
        print(f"largest move relative to its field's scale: {worst[0][0]:.3e}")
        for rel, path, a, b, key in worst[:10]:
            print(f"  {rel:.3e}  {path}  {a!r} -> {b!r}  args {key}")
    for change in structural[:40]:
        print("STRUCTURAL", change)
    return 1 if structural else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
