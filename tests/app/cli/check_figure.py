#!/usr/bin/env python3
"""check_figure.py FILE [--cells N]: a figure written by topoplan is well formed.

FILE.svg: parses as XML with an <svg> root; with --cells N, it has N <rect class="cell">.
FILE.pdf: starts with %PDF and has exactly one page. FILE.png: PNG signature.
Exit 0 when it holds, 1 (with a message) otherwise.
"""
import re
import sys
import xml.etree.ElementTree as ET


def main():
    path = sys.argv[1]
    cells = int(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[2] == "--cells" else None
    data = open(path, "rb").read()
    if path.endswith(".svg"):
        root = ET.fromstring(data)
        if not root.tag.endswith("svg"):
            sys.exit(f"{path}: root element is {root.tag}, not svg")
        if cells is not None:
            n = sum(1 for e in root.iter() if e.tag.endswith("rect") and e.get("class") == "cell")
            if n != cells:
                sys.exit(f"{path}: {n} cells, expected {cells}")
    elif path.endswith(".pdf"):
        if not data.startswith(b"%PDF"):
            sys.exit(f"{path}: does not start with %PDF")
        pages = len(re.findall(rb"/Type\s*/Page[^s]", data))
        if pages != 1:
            sys.exit(f"{path}: {pages} pages, expected 1")
    elif path.endswith(".png"):
        if not data.startswith(b"\x89PNG\r\n\x1a\n"):
            sys.exit(f"{path}: not a PNG")
    else:
        sys.exit(f"{path}: unknown figure type")
    print(f"{path}: ok")


if __name__ == "__main__":
    main()
