#!/usr/bin/python3
"""Turns the report.json files of `rktsph validate --report DIR` into a page people can read.

    make_report.py DIR [CASE ...]

For each case (those named, in that order; without names every DIR/*/report.json, sorted) it
draws the figures the case described to DIR/<case>/<figure>.png, draws its field pictures with
plot_field.py to DIR/<case>/<picture>.png, and writes DIR/index.html and DIR/index.md: what each
case is, its checks (value, reference, tolerance, unit, passed) and its images, by relative path.

The C++ side supplies every number, measured and analytical; this script only draws. A picture
that cannot be drawn is reported on the page in place of the image (and in the exit status).

Exit status: 0 everything drawn, 1 some figure or picture could not be drawn, 2 bad arguments
or no report found.
"""

import html
import json
import math
import os
import subprocess
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("make_report.py: matplotlib is missing: install python3-matplotlib "
             "(make deps-report)")

HERE = os.path.dirname(os.path.abspath(__file__))

# The page counts, once loaded, the images that decoded to a non-zero size, so that a headless
# browser (tools/check_report.sh) can read the result from the DOM.
IMAGE_CHECK_SCRIPT = """<script>
window.addEventListener("load", function () {
  var images = document.querySelectorAll("img");
  var loaded = 0;
  images.forEach(function (image) {
    if (image.complete && image.naturalWidth > 0 && image.naturalHeight > 0) loaded += 1;
  });
  document.body.setAttribute("data-images-total", String(images.length));
  document.body.setAttribute("data-images-loaded", String(loaded));
});
</script>"""

STYLE = """<style>
body { font-family: sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em;
       color: #222; }
table { border-collapse: collapse; margin: 0.8em 0; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: left; }
td.number { text-align: right; font-family: monospace; }
.passed { color: #176f2c; font-weight: bold; }
.failed { color: #b00020; font-weight: bold; }
.error { background: #fde8e8; padding: 0.5em; white-space: pre-wrap; }
figure { margin: 1em 0; }
figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { font-size: 0.9em; color: #444; }
</style>"""


def finite_or_nan(value):
    return float("nan") if value is None else float(value)


def format_number(value):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "n/a"
    return f"{value:.5g}"


def draw_figure(figure, path):
    """One figure of the case: measured series as lines or points, references dashed."""
    plot, axes = plt.subplots(figsize=(8.0, 4.5), dpi=110)
    for series in figure["series"]:
        x = [finite_or_nan(v) for v in series["x"]]
        y = [finite_or_nan(v) for v in series["y"]]
        style = series.get("style", "line")
        if style == "dashed":
            axes.plot(x, y, "--", color="black", linewidth=1.2, label=series["label"])
        elif style == "points":
            axes.plot(x, y, "o", markersize=3, label=series["label"])
        else:
            axes.plot(x, y, "-", linewidth=1.2, label=series["label"])
    axes.set_title(figure.get("title", ""))
    axes.set_xlabel(figure.get("x_label", ""))
    axes.set_ylabel(figure.get("y_label", ""))
    axes.set_xscale(figure.get("x_scale", "linear"))
    axes.set_yscale(figure.get("y_scale", "linear"))
    axes.grid(True, alpha=0.3)
    if figure["series"]:
        axes.legend(loc="best", fontsize="small")
    plot.tight_layout()
    plot.savefig(path)
    plt.close(plot)


def draw_picture(picture, report_directory, path):
    """Runs plot_field.py; returns None or the reason it failed."""
    run_directory = picture["run_directory"]
    if not os.path.isabs(run_directory):
        run_directory = os.path.join(report_directory, run_directory)
    command = [sys.executable, os.path.join(HERE, "plot_field.py"), run_directory,
               "--field", picture["field"], "--component", str(picture.get("component", -1)),
               "--magnify", repr(float(picture.get("magnification", 0.0))), "-o", path]
    time = picture.get("time")
    if time is not None and time >= 0:
        command += ["--time", repr(float(time))]
    finished = subprocess.run(command, capture_output=True, text=True)
    if finished.returncode != 0:
        return finished.stderr.strip() or f"plot_field.py exited with {finished.returncode}"
    return None


def render_case(report_directory, name):
    """Draws the images of one case. Returns its report with the images' outcome added."""
    path = os.path.join(report_directory, name, "report.json")
    try:
        with open(path, encoding="utf-8") as file:
            report = json.load(file)
    except (OSError, ValueError) as problem:
        return {"case": name, "passed": False, "wall_seconds": None, "checks": [],
                "description": "", "figures": [], "pictures": [],
                "error": f"no readable report.json: {problem}", "images": []}
    images = []  # (relative path or None, title, caption, failure)
    for figure in report.get("figures", []):
        relative = f"{name}/{figure['name']}.png"
        try:
            draw_figure(figure, os.path.join(report_directory, relative))
            images.append((relative, figure.get("title", ""), "", None))
        except (ValueError, KeyError, TypeError) as problem:
            images.append((None, figure.get("title", ""), "", f"cannot draw: {problem}"))
    for picture in report.get("pictures", []):
        relative = f"{name}/{picture['name']}.png"
        failure = draw_picture(picture, report_directory,
                               os.path.join(report_directory, relative))
        images.append((None if failure else relative, picture["name"],
                       picture.get("caption", ""), failure))
    report["images"] = images
    return report


def status_html(passed):
    return '<span class="passed">PASSED</span>' if passed else '<span class="failed">FAILED</span>'


def case_html(report):
    escape = html.escape
    parts = [f'<section id="{escape(report["case"])}">',
             f'<h2>{escape(report["case"])} {status_html(report["passed"])}</h2>']
    if report.get("wall_seconds") is not None:
        parts.append(f"<p>Wall time {report['wall_seconds']:.1f} s.</p>")
    if report.get("description"):
        parts.append(f"<p>{escape(report['description'])}</p>")
    if report.get("error"):
        parts.append(f'<p class="error">{escape(report["error"])}</p>')
    if report["checks"]:
        parts.append("<table><tr><th>check</th><th>value</th><th>reference</th>"
                     "<th>tolerance</th><th>unit</th><th>passed</th></tr>")
        for check in report["checks"]:
            parts.append(
                f"<tr><td>{escape(check['name'])}</td>"
                f'<td class="number">{format_number(check["value"])}</td>'
                f'<td class="number">{format_number(check["reference"])}</td>'
                f'<td class="number">{format_number(check["tolerance"])}</td>'
                f"<td>{escape(check['unit'])}</td>"
                f"<td>{status_html(check['passed'])}</td></tr>")
        parts.append("</table>")
    for relative, title, caption, failure in report["images"]:
        if failure:
            parts.append(f'<p class="error">{escape(title)}: {escape(failure)}</p>')
            continue
        text = caption or title
        parts.append(f'<figure><img src="{escape(relative)}" alt="{escape(title)}">'
                     f"<figcaption>{escape(text)}</figcaption></figure>")
    parts.append("</section>")
    return "\n".join(parts)


def write_html(report_directory, reports):
    passed = sum(1 for report in reports if report["passed"])
    rows = "\n".join(
        f'<tr><td><a href="#{html.escape(r["case"])}">{html.escape(r["case"])}</a></td>'
        f"<td>{status_html(r['passed'])}</td>"
        f"<td>{sum(1 for c in r['checks'] if c['passed'])} / {len(r['checks'])}</td></tr>"
        for r in reports)
    page = f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>rktsph validation report</title>
{STYLE}
</head>
<body>
<h1>rktsph validation report</h1>
<p>{passed} of {len(reports)} cases passed. Each case compares what the simulation measured with
an analytical or independent reference (docs/validation.md); dashed black curves are the
references.</p>
<table><tr><th>case</th><th>status</th><th>checks passed</th></tr>
{rows}
</table>
{"".join(case_html(report) + chr(10) for report in reports)}
{IMAGE_CHECK_SCRIPT}
</body>
</html>
"""
    with open(os.path.join(report_directory, "index.html"), "w", encoding="utf-8") as file:
        file.write(page)


def markdown_cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def write_markdown(report_directory, reports):
    lines = ["# rktsph validation report", "",
             f"{sum(1 for r in reports if r['passed'])} of {len(reports)} cases passed. "
             "Dashed black curves are the references.", "",
             "| case | status | checks passed |", "|---|---|---|"]
    for report in reports:
        lines.append(f"| [{report['case']}](#{report['case']}) | "
                     f"{'PASSED' if report['passed'] else 'FAILED'} | "
                     f"{sum(1 for c in report['checks'] if c['passed'])} / "
                     f"{len(report['checks'])} |")
    for report in reports:
        lines += ["", f"## {report['case']}", "",
                  f"**{'PASSED' if report['passed'] else 'FAILED'}**"
                  + (f", wall time {report['wall_seconds']:.1f} s."
                     if report.get("wall_seconds") is not None else "")]
        if report.get("description"):
            lines += ["", report["description"]]
        if report.get("error"):
            lines += ["", f"Error: `{markdown_cell(report['error'])}`"]
        if report["checks"]:
            lines += ["", "| check | value | reference | tolerance | unit | passed |",
                      "|---|---:|---:|---:|---|---|"]
            for check in report["checks"]:
                lines.append(
                    f"| {markdown_cell(check['name'])} | {format_number(check['value'])} | "
                    f"{format_number(check['reference'])} | {format_number(check['tolerance'])} "
                    f"| {markdown_cell(check['unit'])} | {'yes' if check['passed'] else 'NO'} |")
        for relative, title, caption, failure in report["images"]:
            if failure:
                lines += ["", f"{title}: could not be drawn: {markdown_cell(failure)}"]
            else:
                lines += ["", f"![{markdown_cell(title)}]({relative})"]
                if caption:
                    lines += ["", f"*{caption}*"]
    with open(os.path.join(report_directory, "index.md"), "w", encoding="utf-8") as file:
        file.write("\n".join(lines) + "\n")


def main(arguments):
    if not arguments or arguments[0].startswith("-"):
        print(__doc__, file=sys.stderr)
        return 2
    report_directory, names = arguments[0], arguments[1:]
    if not names:
        names = sorted(entry for entry in os.listdir(report_directory)
                       if os.path.isfile(os.path.join(report_directory, entry, "report.json")))
    if not names:
        print(f"make_report.py: no <case>/report.json under {report_directory}", file=sys.stderr)
        return 2
    reports = [render_case(report_directory, name) for name in names]
    write_html(report_directory, reports)
    write_markdown(report_directory, reports)
    failures = [(report["case"], title, failure) for report in reports
                for _, title, _, failure in report["images"] if failure]
    for case, title, failure in failures:
        print(f"make_report.py: {case}/{title}: {failure}", file=sys.stderr)
    images = sum(len(report["images"]) for report in reports)
    print(f"Report: {os.path.join(report_directory, 'index.html')} ({len(reports)} cases, "
          f"{images - len(failures)} images)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
