#!/usr/bin/env python3
"""Function-size check (ctest `arch.function-size`, label `arch`; docs/ARCHITECTURE.md "Layers").

No function in the folders of CHECKED may be longer than LIMIT lines (from the first line of its signature to
its closing brace). Every longer one is printed as `file:line: function NAME is N lines (limit LIMIT)` and
the check fails (exit 1).

The scanner is plain Python, made for this code base's style (clang-format, one definition per signature):
comments, string and character literals (raw strings too) and preprocessor lines are blanked first; then
the braces are followed with a stack of scopes. A `{` outside any function opens

  a namespace, class, struct, union or enum   when its head starts with that keyword (after `template <..>`),
  a brace initialiser                         when its head holds an `=` or it is a member's initialiser in a
                                              constructor's `) : a_(x), b_{y}` list,
  a function body                             when its head holds a `(` (the name is the identifier before it),

and everything inside a function body (blocks, lambdas, local classes) counts as the function's.

Before the tree it checks itself on a small synthetic source (SELF_TEST), so a scanner that stopped finding
functions fails the test rather than passing everything.

Usage: check_function_size.py [SOURCE_DIR] [--limit N]   (default: the repository this script is in, 120)
"""

import os
import re
import sys

LIMIT = 120
CHECKED = ["adapter", os.path.join("coupling", "mapping")]
EXTENSIONS = (".C", ".H", ".cpp", ".hpp", ".h", ".cc")


def blank_non_code(text):
    """The text with comments, literals and preprocessor lines replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":  # preprocessor line, with its continuations
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        if c == "\n":
            out.append(c)
            at_line_start = True
            i += 1
            continue
        if c in " \t":
            out.append(c)
            i += 1
            continue
        at_line_start = False
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
            close = ")" + raw.group(1) + '"'
            end = text.find(close, i + raw.end())
            end = n if end < 0 else end + len(close)
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        if c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):  # 1'000 is a number
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


SCOPE_HEAD = re.compile(r"^(?:(?:template\s*<.*>\s*)?(?:inline\s+)?(?:namespace|class|struct|union|enum)\b|extern\s*$)",
                        re.S)
NAME_BEFORE_PAREN = re.compile(r"((?:operator\s*(?:\(\)|[^\s(]+))|~?[A-Za-z_]\w*)\s*\($")
CTOR_INIT = re.compile(r"\)\s*(?:noexcept\s*)?:(?!:)")


def function_name(head):
    """The name of the function whose head (signature) this is: the identifier before its first `(`."""
    head = re.sub(r"^template\s*<[^{]*?>\s*", "", head.strip())
    depth = 0
    for k, c in enumerate(head):
        if c == "<":
            depth += 1
        elif c == ">":
            depth = max(0, depth - 1)
        elif c == "(" and depth == 0:
            m = NAME_BEFORE_PAREN.search(head[:k + 1])
            if m:
                qualified = re.search(r"([\w:~]*" + re.escape(m.group(1)) + r")\s*\($", head[:k + 1])
                return qualified.group(1) if qualified else m.group(1)
    return head.split("(")[0].split()[-1] if "(" in head and head.split("(")[0].split() else "?"


def functions(text):
    """(name, first line, last line) of every function defined in `text` (C++ source)."""
    code = blank_non_code(text)
    found = []
    stack = []  # kinds: "scope", "init", "function", "block" (inside a function)
    head, head_line = [], None
    line = 1
    for c in code:
        if c == "\n":
            line += 1
            if head:
                head.append(" ")
            continue
        in_function = any(k[0] == "function" for k in stack)
        if c == "{":
            if in_function:
                stack.append(("block", line))
                continue
            h = "".join(head).strip()
            if SCOPE_HEAD.match(h):
                stack.append(("scope", line))
                head, head_line = [], None
            elif CTOR_INIT.search(h) and re.search(r"[\w>]\s*$", h) and not re.search(
                    r"\)\s*(?:const|override|final|noexcept|\s)*$", h):
                stack.append(("member-init", line))  # b_{y} in `) : a_(x), b_{y} {`: the head goes on
                head.append(c)
            elif "=" in re.sub(r"operator\s*[=!<>+\-*/%^&|]*=|[=!<>]=", "", h) or "(" not in h:
                stack.append(("init", line))
                head.append(c)
            else:
                stack.append(("function", line, function_name(h), head_line or line))
                head, head_line = [], None
            continue
        if c == "}":
            if not stack:
                continue
            top = stack.pop()
            if top[0] == "function":
                found.append((top[2], top[3], line))
            elif top[0] in ("member-init", "init"):
                head.append(c)
            elif top[0] == "scope":
                head, head_line = [], None
            continue
        if in_function:
            continue
        if c == ";" and not (stack and stack[-1][0] in ("init", "member-init")):
            head, head_line = [], None
            continue
        if stack and stack[-1][0] in ("init", "member-init"):
            continue
        if c == ":" and re.fullmatch(r"\s*(?:public|private|protected)\s*", "".join(head)):
            head, head_line = [], None  # an access specifier is no part of the next declaration
            continue
        if not head and not c.isspace():
            head_line = line
        if head or not c.isspace():
            head.append(c)
    return found


SELF_TEST = """// A file the scanner must read right: braces in comments { and strings, init lists, lambdas, long bodies.
#include <string>
#define BLOCK { {
namespace demo {
/* } not a brace */
struct Options {
  int a = 1;
  std::string s = "}{";
  char c = '{';
};
class Widget {
 public:
  Widget(int a, int b) : a_(a), b_{b}, c_{} {
    auto f = [&] { return a_ + 1; };
    (void)f;
  }
  int small() const override { return R"x( } )x"[0] == ' ' ? 1 : 0; }
 private:
  int a_, b_, c_;
};
static const int table[] = {1, 2, 3};
template <int K>
int Widget::long(int x) {
@LONG@
  return x;
}
}  // namespace demo
"""


def self_test(limit):
    """The scanner on SELF_TEST: every function found with its lines; the long one flagged. Returns errors."""
    body = "\n".join("  x += %d; if (x) { x -= 1; }" % k for k in range(limit + 5))
    text = SELF_TEST.replace("@LONG@", body)
    got = {name: (first, last) for name, first, last in functions(text)}
    errors = []
    expect = {"Widget": (13, 16), "small": (17, 17), "Widget::long": (22, 22 + limit + 5 + 3)}
    for name, lines in expect.items():
        if got.get(name) != lines:
            errors.append("self-test: function %s found at lines %s, expected %s" % (name, got.get(name), lines))
    for name in got:
        if name not in expect:
            errors.append("self-test: %s taken for a function" % name)
    long_ones = [n for n, (a, b) in got.items() if b - a + 1 > limit]
    if long_ones != ["Widget::long"]:
        errors.append("self-test: the functions over the limit are %s, expected ['Widget::long']" % long_ones)
    return errors


def main(argv):
    args = [a for a in argv[1:]]
    limit = LIMIT
    if "--limit" in args:
        k = args.index("--limit")
        limit = int(args[k + 1])
        del args[k:k + 2]
    root = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), "..", ".."))
    errors = self_test(limit)
    if errors:
        print("\n".join(errors))
        print("check_function_size.py: the scanner itself is wrong (its self-test failed)")
        return 1
    bad, count, longest = [], 0, (0, "", "")
    for folder in CHECKED:
        base = os.path.join(root, folder)
        if not os.path.isdir(base):
            print("check_function_size.py: no folder %s" % base)
            return 1
        for dirpath, _, files in sorted(os.walk(base)):
            for f in sorted(files):
                if not f.endswith(EXTENSIONS):
                    continue
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, root)
                with open(path, encoding="utf-8") as fh:
                    for name, first, last in functions(fh.read()):
                        count += 1
                        size = last - first + 1
                        if size > longest[0]:
                            longest = (size, "%s:%d" % (rel, first), name)
                        if size > limit:
                            bad.append("%s:%d: function %s is %d lines (limit %d)" % (rel, first, name, size, limit))
    if count == 0:
        print("check_function_size.py: no functions found under %s" % ", ".join(CHECKED))
        return 1
    for b in bad:
        print(b)
    print("%d functions in %s; the longest: %s at %s, %d lines (limit %d)" %
          (count, ", ".join(CHECKED), longest[2], longest[1], longest[0], limit))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
