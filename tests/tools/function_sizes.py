#!/usr/bin/env python3
"""Function sizes of the project's .cpp files: count, median, p90 and the longest.

    python3 tests/tools/function_sizes.py [ROOT] [--top N]

ROOT is the repository (default: the one this script lives in); the files measured are the
.cpp files under ROOT's mesh/, radiosity/ and display/.

The rule. A function's size is the number of lines of its body, from the line holding the
opening `{` to the line holding its closing `}` (a body on one line is 1). Counted are the
function definitions at namespace level (any namespace, named or anonymous, or none) and the
member functions defined outside their class (`void Foo::bar() {`). Not counted: member
functions defined inside a class body, lambdas, and anything else inside a function (their
lines belong to the function around them).

The parser is a simple brace matcher, not a C++ parser. Comments, string and character
literals (raw strings too) and preprocessor lines are blanked first, so their braces do not
count. Each `{` is then classified by the text since the previous `;`, `{` or `}` of its scope
(its head): `namespace ...` or `extern "C"` opens a namespace (looked through); a head that
starts with class/struct/union/enum (after any `template <...>`) opens a class; a head with a
parenthesis and no `=` before its first parenthesis (outside `operator...`) opens a function,
whose body is the first `{` after a `)` or after a member initialiser's `}` (in a
constructor's initialiser list `x{...}` braces are skipped); anything else (an initialiser
`= {...}`) is a plain block.

Figures: the median is the statistics module's (the mean of the middle two for an even
count); p90 is the nearest-rank 90th percentile (the smallest size at least 90 % of the
functions do not exceed).
"""

import argparse
import math
import os
import re
import statistics
import sys

FOLDERS = ("mesh", "radiosity", "display")


def blank(text):
    """The text with comments, string/char literals and preprocessor lines replaced by spaces
    (newlines kept, so that line numbers hold). String literals keep their quotes ("")."""
    out = []
    i, n = 0, len(text)
    line_start = True  # only whitespace since the last newline
    while i < n:
        c = text[i]
        if c == "\n":
            out.append(c)
            i += 1
            line_start = True
            continue
        if line_start and c == "#":  # a preprocessor line, with its continuations
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        if not c.isspace():
            line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        raw = re.match(r'(?:u8|u|U|L)?R"([^()\\\s]{0,16})\(', text[i:i + 24])
        if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            end = text.find(")" + raw.group(1) + '"', i + raw.end())
            end = n if end < 0 else end + len(raw.group(1)) + 2
            out.append('""' + re.sub(r"[^\n]", " ", text[i + 2:end]))
            i = end
            continue
        if c == '"' or (c == "'" and not digit_separator(text, i)):
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else c)
            i = j
            continue
        out.append(c)
        i += 1
    return "".join(out)


def digit_separator(text, i):
    """Whether the quote at text[i] separates digits (1'000) rather than opening a char literal."""
    k = i
    while k > 0 and (text[k - 1].isalnum() or text[k - 1] in "_'"):
        k -= 1
    return k < i and text[k].isdigit() and i + 1 < len(text) and text[i + 1].isalnum()


def strip_template_prefix(head):
    """The head without leading `template <...>` clauses."""
    while True:
        m = re.match(r"\s*template\s*<", head)
        if not m:
            return head
        depth, k = 1, m.end()
        while k < len(head) and depth:
            depth += {"<": 1, ">": -1}.get(head[k], 0)
            k += 1
        head = head[k:]


def kind_of(head):
    """What a `{` with this head opens: 'namespace', 'class', 'function' or 'block'."""
    h = strip_template_prefix(head).strip()
    if re.match(r"(inline\s+)?namespace\b", h) or re.match(r'extern\s*"', h):
        return "namespace"
    if re.match(r"(typedef\s+)?(class|struct|union|enum)\b", h) and "(" not in re.sub(r"alignas\s*\([^)]*\)", "", h):
        return "class"
    if "(" not in h:
        return "block"
    before = re.sub(r"operator\s*(\(\s*\)|[^\s(]+)", "operator", h).split("(", 1)[0]
    if "=" in before:
        return "block"
    return "function"


def functions(text):
    """(first line, lines) of each counted function body in the blanked text."""
    found = []
    stack = []  # per open brace: (kind, line it opened on)
    head_start = 0
    line = 1
    skip = 0  # open member-initialiser braces inside a function head
    i = 0
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        elif c in ";":
            if not skip:
                head_start = i + 1
        elif c == "{":
            scope = stack[-1][0] if stack else "namespace"
            if skip or scope not in ("namespace", "class"):
                if skip:
                    skip += 1
                stack.append(("inner", line))
                continue
            head = text[head_start:i]
            kind = kind_of(head)
            if kind == "function" and re.search(r"\)[^()]*?:(?!:)", head.replace("::", "  ")):
                # A constructor's initialiser list: `x{` initialises a member, the body
                # follows a `)` or a `}`.
                prev = head.rstrip()[-1:] if head.rstrip() else ""
                if prev and (prev.isalnum() or prev in "_>"):
                    skip = 1
                    stack.append(("inner", line))
                    continue
            if kind == "function" and scope == "class":
                kind = "inline-member"
            stack.append((kind, line))
            head_start = i + 1
        elif c == "}":
            if not stack:
                continue
            kind, opened = stack.pop()
            if skip:
                skip -= 1
                continue
            if kind == "function":
                found.append((opened, line - opened + 1))
            if not stack or stack[-1][0] in ("namespace", "class"):
                head_start = i + 1
    return found


def nearest_rank(sorted_values, share):
    return sorted_values[max(0, math.ceil(share * len(sorted_values)) - 1)]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root", nargs="?", default=os.path.dirname(os.path.dirname(here)))
    parser.add_argument("--top", type=int, default=0, help="also list the N longest functions")
    args = parser.parse_args()
    sizes = []  # (lines, path, line)
    for folder in FOLDERS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(args.root, folder)):
            dirnames.sort()
            for name in sorted(filenames):
                if not name.endswith(".cpp"):
                    continue
                path = os.path.join(dirpath, name)
                with open(path, encoding="utf-8", errors="replace") as f:
                    text = blank(f.read())
                rel = os.path.relpath(path, args.root)
                sizes += [(lines, rel, first) for first, lines in functions(text)]
    if not sizes:
        sys.exit("function_sizes: no functions found under " + args.root)
    values = sorted(s[0] for s in sizes)
    longest = max(sizes, key=lambda s: s[0])
    print(f"functions: {len(values)}")
    print(f"median:    {statistics.median(values):g} lines")
    print(f"p90:       {nearest_rank(values, 0.9)} lines")
    print(f"longest:   {longest[0]} lines, {longest[1]}:{longest[2]}")
    for lines, rel, first in sorted(sizes, key=lambda s: -s[0])[:args.top]:
        print(f"  {lines:4d}  {rel}:{first}")


if __name__ == "__main__":
    main()
