#!/usr/bin/env python3
"""Checks that the files CMake compiles together in a unity build cannot see each other's names.

A unity build (TOPOPLAN_UNITY) compiles several .cc files of one library as one translation unit,
so a name in one file's anonymous namespace becomes visible in the others. Two identical
definitions fail to compile, but two functions of one name with different parameters silently
become overloads, and a call in one file may pick the other file's function. This script fails
(exit 1) when, within one library's unity batches:
  - two files define the same name in their anonymous namespaces (except one alias,
    `using X = T;`, written identically), or
  - a file's anonymous-namespace name equals a name declared at namespace scope in a header of
    the library's folders (the file would overload or hide it for its batch neighbours), again
    except an identical alias.

Usage: check_unity_names.py BUILD_DIR SOURCE_DIR
       check_unity_names.py --self-test   (the check on a made-up library with known clashes)
  Reads BUILD_DIR/**/<target>.dir/Unity/unity_*.cxx (the batch files CMake writes) to learn which
  sources share a library; exit 0 with a note when there are none (TOPOPLAN_UNITY=OFF).
The scan is textual: it tracks braces (comments and literals blanked) and takes the names declared
at column 0 directly inside a namespace, which is where clang-format (Google style) puts them.
"""
import collections
import os
import re
import sys

OPEN = re.compile(r"^namespace\s*\{")
CLOSE = re.compile(r"^\}\s*//\s*namespace\s*$")
TYPE = re.compile(r"^(?:template\s*<.*>\s*)?(?:struct|class|enum(?:\s+class)?|union)\s+(\w+)")
ALIAS = re.compile(r"^using\s+(\w+)\s*=")
CONST = re.compile(
    r"^(?:static\s+)?(?:inline\s+)?(?:constexpr|const)\s+[\w:<>,*&][\w:<>,\s*&]*?\s(\w+)"
    r"(?:\[.*\])?\s*(?:=|\{|\()")
FUNC = re.compile(
    r"^(?:template\s*<.*>\s*)?(?:\[\[\w+\]\]\s*)?(?:static\s+)?(?:inline\s+)?(?:constexpr\s+)?"
    r"[A-Za-z_][\w:<>,*&\s]*?[\s*&](\w+)\s*\(")
KEYWORDS = {"if", "for", "while", "switch", "return", "operator", "main"}


def declared_name(line):
    for pattern in (TYPE, ALIAS, CONST, FUNC):
        m = pattern.match(line)
        if m and m.group(1) not in KEYWORDS:
            return m.group(1)
    return None


def _code(text):
    """The text with comments, string and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            k = text.find("(", i)
            delim = ")" + text[i + 2:k] + '"'
            j = text.find(delim, k)
            j = n if j < 0 else j + len(delim)
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def scoped_names(path):
    """(anonymous, public): names declared at column 0 directly in an anonymous namespace, and
    directly in a named namespace (or at file scope)."""
    with open(path, encoding="utf-8") as f:
        code = _code(f.read())
    anonymous, public = set(), set()
    aliases = {}  # alias name -> its declaration, for the identical-alias exception
    stack = []  # per open brace: "anon", "named" or "other"
    pending = ""  # text since the last ; { or }
    for line in code.split("\n"):
        if line.lstrip().startswith("#"):  # preprocessor lines are not part of any declaration
            continue
        if stack == [] or stack[-1] in ("anon", "named"):
            name = declared_name(line)
            if name:
                in_anonymous = "anon" in stack
                (anonymous if in_anonymous else public).add(name)
                if ALIAS.match(line):
                    aliases[name] = " ".join(line.split())
        for ch in line + "\n":
            if ch == "{":
                head = pending.strip()
                if re.fullmatch(r"(inline\s+)?namespace", head):
                    stack.append("anon")
                elif re.fullmatch(r"(inline\s+)?namespace\s+[\w:]+|extern\s*\"\"", head):
                    stack.append("named")
                else:
                    stack.append("other")
                pending = ""
            elif ch == "}":
                if stack:
                    stack.pop()
                pending = ""
            elif ch == ";":
                pending = ""
            else:
                pending += ch
    return anonymous, public, aliases


def anonymous_names(path):
    """{name: declaration text for aliases, else None} of the file's anonymous namespaces."""
    anonymous, _, aliases = scoped_names(path)
    return {n: aliases.get(n) for n in anonymous}


def public_names(directories):
    """Namespace-scope names declared in the headers under `directories`:
    {name: (header, declaration text for aliases, else None)}."""
    out = {}
    for top in directories:
        for root, _, files in os.walk(top):
            for name in sorted(files):
                if name.endswith(".h"):
                    path = os.path.join(root, name)
                    _, public, aliases = scoped_names(path)
                    for n in public:
                        out.setdefault(n, (path, aliases.get(n)))
    return out


def unity_targets(build_dir):
    """{target directory: [source files]} from CMake's unity batch files."""
    targets = collections.defaultdict(list)
    include = re.compile(r'^#include "(.+)"')
    for root, _, files in os.walk(build_dir):
        if os.path.basename(root) != "Unity":
            continue
        for name in sorted(files):
            if not re.match(r"unity_\d+_cxx\.cxx$", name):
                continue
            with open(os.path.join(root, name), encoding="utf-8") as f:
                for line in f:
                    m = include.match(line)
                    if m:
                        targets[os.path.dirname(root)].append(m.group(1))
    return targets


def self_test():
    """The check on a made-up library: two files with an overloaded helper, a clash with a header
    name, an identical alias (allowed) and names in nested scopes (ignored). Exit 0 when it finds
    exactly the two problems."""
    import io
    import contextlib
    import tempfile
    with tempfile.TemporaryDirectory() as root:
        src = os.path.join(root, "lib")
        unity = os.path.join(root, "build", "lib.dir", "Unity")
        os.makedirs(src)
        os.makedirs(unity)
        files = {
            "api.h": "namespace lib {\nint Public(int x);\nusing Json = int;\n}  // namespace lib\n",
            "a.cc": ('#include "api.h"\nnamespace lib {\nnamespace {\nusing Json = int;\n'
                     "double Helper(double x) { return x; }\nstruct Local {\n  int Inner();\n};\n"
                     "}  // namespace\n}  // namespace lib\n"),
            "b.cc": ('namespace lib {\nnamespace {\nusing Json = int;\n'
                     'const char* kText = "namespace {";\nint Helper(int x) {\n  return x;\n}\n'
                     "int Public(int x) { return x; }\n}  // namespace\n}  // namespace lib\n"),
        }
        for name, text in files.items():
            with open(os.path.join(src, name), "w", encoding="utf-8") as f:
                f.write(text)
        with open(os.path.join(unity, "unity_0_cxx.cxx"), "w", encoding="utf-8") as f:
            f.write(f'#include "{src}/a.cc"\n#include "{src}/b.cc"\n')
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            rc = main(["check", os.path.join(root, "build"), root])
    text = out.getvalue()
    ok = (rc == 1 and "Helper: in the anonymous namespaces of lib/a.cc, lib/b.cc" in text and
          "Public: in the anonymous namespace of lib/b.cc, and declared in lib/api.h" in text and
          "2 name(s)" in text)
    print(text, end="")
    print("check_unity_names --self-test: " + ("ok" if ok else "FAILED"))
    return 0 if ok else 1


def main(argv):
    if len(argv) == 2 and argv[1] == "--self-test":
        return self_test()
    if len(argv) != 3 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) == 2 else 2
    build_dir, source_dir = argv[1], argv[2]
    targets = unity_targets(build_dir)
    if not targets:
        print("check_unity_names: no unity batches in " + build_dir + " (TOPOPLAN_UNITY=OFF)")
        return 0
    problems = []
    for target, sources in sorted(targets.items()):
        dirs = sorted({os.path.dirname(src) for src in sources})
        public = public_names(d for d in dirs if not any(d.startswith(o + os.sep) for o in dirs))
        owners = collections.defaultdict(list)
        alias_texts = collections.defaultdict(set)
        for src in sources:
            for n, alias in anonymous_names(src).items():
                owners[n].append(os.path.relpath(src, source_dir))
                alias_texts[n].add(alias)
        for n, files in sorted(owners.items()):
            # The same alias to the same type, redeclared, is legal and means the same everywhere.
            same_alias = len(alias_texts[n]) == 1 and None not in alias_texts[n]
            if len(files) > 1 and not same_alias:
                problems.append(f"{n}: in the anonymous namespaces of {', '.join(files)}")
            if n in public and not (same_alias and alias_texts[n] == {public[n][1]}):
                problems.append(f"{n}: in the anonymous namespace of {files[0]}, and declared in "
                                f"{os.path.relpath(public[n][0], source_dir)}")
    count = sum(len(s) for s in targets.values())
    if problems:
        print(f"check_unity_names: {len(problems)} name(s) that unity batches would share:")
        for p in problems:
            print("  " + p)
        print("Give each a unique name (or move shared code to a header).")
        return 1
    print(f"check_unity_names: {count} files in {len(targets)} unity libraries, no shared names")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
