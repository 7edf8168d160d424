#!/usr/bin/python3
"""Keeps the sources readable: no C++ file in src over 650 lines, no function over 150 lines.

    size_test.py SRC_DIR [--max-file N] [--max-function N]

Functions are found by a brace scanner (comments, string and character literals removed first):
a block opened after a parenthesised signature, outside any other function, that is not a
control statement or an initialiser. Its length counts from the line of the signature's name to
the closing brace (a constructor whose member initialisers use braces is not measured). Prints each violation as FILE:LINE and exits 1 when there is one; exit 2 on bad
usage. `--self-test` checks the scanner on small hand-made sources.
"""
import argparse
import pathlib
import re
import sys

CONTAINER = re.compile(r"\b(namespace|class|struct|union|enum)\b[^()]*$|extern\s+\"C\"\s*$")
CONTROL = re.compile(r"^\s*(if|for|while|switch|catch|do|else|return|try)\b|\b(if|for|while|switch|catch)\s*\(")


def strip(text):
    """The text with comments and literals blanked, newlines kept (line numbers stay right)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + re.sub(r"[^\n]", " ", text[i + 2:j])); i = j
        elif c in "\"'":
            if c == "'" and i > 0 and (text[i - 1].isalnum()):  # digit separator 1'000
                out.append(c); i += 1; continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (j - i - 1) + c); i = j + 1
        else:
            out.append(c); i += 1
    return "".join(out)


def functions(text):
    """(name, first line, last line) of each outermost function body in a C++ source."""
    code = strip(text)
    found, stack = [], []  # stack of (kind, start line, name)
    head_start = 0  # where the text leading to the next brace begins
    line_of = lambda pos: code.count("\n", 0, pos) + 1
    for i, c in enumerate(code):
        if c in ";":
            head_start = i + 1
        elif c == "{":
            head = code[head_start:i]
            in_function = any(k == "function" for k, _, _ in stack)
            kind = "block"
            flat = " ".join(head.split())
            if not in_function and "(" in flat and not CONTAINER.search(flat) and not CONTROL.search(flat) \
                    and not re.search(r"=\s*$", flat) and not flat.startswith(("#", "=")):
                kind = "function"
            elif not in_function and CONTAINER.search(flat):
                kind = "container"
            name, first = "", line_of(i)
            if kind == "function":
                m = re.search(r"([~\w:<>]+)\s*\(", flat)
                name = m.group(1) if m else "?"
                lead = len(head) - len(head.lstrip())
                at = head.lstrip().find(name.split("::")[-1]) if m else -1
                first = line_of(head_start + lead + max(at, 0))
            stack.append((kind, first, name))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, first, name = stack.pop()
                if kind == "function":
                    found.append((name, first, line_of(i)))
            head_start = i + 1
    return found


def self_test():
    src = """namespace a {
// a comment { with a brace
int f(int x) {
  if (x) { return 1; }
  auto g = [](int y) { return y; };
  const char* s = "}{";
  return g(x);
}
struct S {
  int m() const { return 2; }
};
int table[] = {1, 2};
}  // namespace a
"""
    got = [(n, a, b) for n, a, b in functions(src)]
    want = [("f", 3, 8), ("m", 10, 10)]
    if got != want:
        print(f"self-test: scanner found {got}, expected {want}")
        return 1
    print("self-test: scanner finds f (3-8) and S::m (10), skips lambdas, literals and tables")
    return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("src", nargs="?")
    ap.add_argument("--max-file", type=int, default=650)
    ap.add_argument("--max-function", type=int, default=150)
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    if not a.src or not pathlib.Path(a.src).is_dir():
        print("usage: size_test.py SRC_DIR", file=sys.stderr)
        return 2
    bad = 0
    files = sorted(p for p in pathlib.Path(a.src).rglob("*") if p.suffix in (".cpp", ".hpp", ".h", ".cc"))
    longest = ("", 0)
    for p in files:
        text = p.read_text(encoding="utf-8", errors="replace")
        lines = text.count("\n")
        if lines > a.max_file:
            print(f"{p}:1: {lines} lines (at most {a.max_file} in one file)")
            bad += 1
        for name, first, last in functions(text):
            length = last - first + 1
            if length > longest[1]:
                longest = (f"{p}:{first} {name}", length)
            if length > a.max_function:
                print(f"{p}:{first}: function {name} is {length} lines (at most {a.max_function})")
                bad += 1
    print(f"{len(files)} files; longest function {longest[1]} lines ({longest[0]}); {bad} over the limits")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
