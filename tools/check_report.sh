#!/usr/bin/env bash
# Checks that a validation report (tools/make_report.py) looks right in a browser:
#   tools/check_report.sh DIR
#
# 1. Every <img src> of DIR/index.html names a file under DIR that is a PNG with a non-zero size.
# 2. Headless Chromium loads the page and, after its load event, every <img> in the DOM has a
#    non-zero natural size (the page's own script writes the counts into <body data-images-*>,
#    read back with --dump-dom).
# 3. A screenshot of the page, DIR/page-screenshot.png, is taken and must not be blank; look at
#    it to see what a reader sees.
# Needs chromium and python3-matplotlib (`make deps-report`). Exits non-zero on any failure.
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 REPORT_DIR" >&2
  exit 2
fi
report_dir=$(cd "$1" && pwd)
page="$report_dir/index.html"
[ -f "$page" ] || { echo "check_report: $page does not exist" >&2; exit 1; }
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "check_report: chromium is not installed (make deps-report)" >&2
  exit 1
fi

profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
browser_flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
               --disable-background-networking --disable-component-update --disable-sync
               --user-data-dir="$profile")

# 1. The files behind the <img> tags.
expected=$(/usr/bin/python3 - "$page" <<'EOF'
import html.parser
import os
import struct
import sys

page = sys.argv[1]
base = os.path.dirname(page)


class Images(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.sources = []

    def handle_starttag(self, tag, attributes):
        if tag == "img":
            self.sources.append(dict(attributes).get("src", ""))


parser = Images()
with open(page, encoding="utf-8") as file:
    parser.feed(file.read())
problems = []
for source in parser.sources:
    if not source or os.path.isabs(source) or ":" in source:
        problems.append(f"{source!r}: not a relative path")
        continue
    path = os.path.join(base, source)
    try:
        with open(path, "rb") as file:
            head = file.read(24)
    except OSError as error:
        problems.append(f"{source}: {error.strerror}")
        continue
    # PNG signature, then the IHDR chunk with width and height (big-endian).
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        problems.append(f"{source}: not a PNG file")
        continue
    width, height = struct.unpack(">II", head[16:24])
    if width == 0 or height == 0:
        problems.append(f"{source}: PNG of size {width} x {height}")
for problem in problems:
    print(f"check_report: {problem}", file=sys.stderr)
print(len(parser.sources))
sys.exit(1 if problems else 0)
EOF
)

# 2. The browser's view of the same images. The virtual time budget lets the load event fire
# before the DOM is printed.
dom=$("$browser" "${browser_flags[@]}" --virtual-time-budget=10000 --dump-dom \
      "file://$page" 2>/dev/null)
total=$(printf '%s' "$dom" | sed -n 's/.*data-images-total="\([0-9]*\)".*/\1/p' | head -n 1)
loaded=$(printf '%s' "$dom" | sed -n 's/.*data-images-loaded="\([0-9]*\)".*/\1/p' | head -n 1)
if [ -z "$total" ] || [ -z "$loaded" ]; then
  echo "check_report: the page's image check did not run in Chromium" >&2
  exit 1
fi
if [ "$total" != "$expected" ] || [ "$loaded" != "$total" ]; then
  echo "check_report: Chromium loaded $loaded of $total images ($expected <img> in the file)" >&2
  exit 1
fi

# 3. A screenshot, which must show more than one colour.
screenshot="$report_dir/page-screenshot.png"
rm -f "$screenshot"
"$browser" "${browser_flags[@]}" --hide-scrollbars --window-size=1280,2400 \
  --virtual-time-budget=10000 --screenshot="$screenshot" "file://$page" >/dev/null 2>&1 || true
/usr/bin/python3 - "$screenshot" <<'EOF'
import sys

import matplotlib.image

try:
    pixels = matplotlib.image.imread(sys.argv[1])
except (OSError, ValueError, SyntaxError) as error:
    sys.exit(f"check_report: no usable screenshot: {error}")
if pixels.size == 0 or float(pixels.std()) == 0.0:
    sys.exit("check_report: the screenshot is blank")
EOF

echo "check_report: $loaded of $total images load in Chromium; screenshot: $screenshot"
