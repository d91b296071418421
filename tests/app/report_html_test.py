#!/usr/bin/env python3
"""Opens a campaign's report.html in headless Chromium (Debian's `chromium`) and checks that it
renders without script errors, that every image loads and that the summary table is there.

usage: report_html_test.py DTWIRE CAMPAIGN.toml WORKDIR [--screenshot PNG]

Runs `DTWIRE campaign CAMPAIGN.toml -o WORKDIR/out` first (a small fixture campaign in the
test), then `chromium --headless --dump-dom` on the report: the page's own script records, on
the load event, how many images loaded (body data-images="loaded/total") and how many errors
were raised (body data-errors). No network is used: the page embeds its images.
"""
import html.parser
import os
import re
import shutil
import subprocess
import sys


class Dom(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.body = {}
        self.images = 0
        self.stack = []
        self.summary_tables = 0
        self.summary_headings = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "body":
            self.body = attrs
        if tag == "img":
            self.images += 1
        if tag == "section" and attrs.get("id") == "summary":
            self.stack.append("summary")
        elif tag == "section":
            self.stack.append("other")
        if "summary" in self.stack and tag == "table":
            self.summary_tables += 1
        if "summary" in self.stack and tag == "h3":
            self.summary_headings.append(attrs.get("id", ""))

    def handle_endtag(self, tag):
        if tag == "section" and self.stack:
            self.stack.pop()


def chromium(*arguments, profile):
    browser = shutil.which("chromium")
    if not browser:
        sys.exit("chromium not found: it is installed by scripts/setup (Debian package chromium)")
    command = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
               "--disable-background-networking", "--disable-component-update", "--disable-sync",
               "--user-data-dir=" + profile, *arguments]
    return subprocess.run(command, capture_output=True, text=True, timeout=120)


def main():
    args = sys.argv[1:]
    screenshot = None
    if "--screenshot" in args:
        at = args.index("--screenshot")
        screenshot = args[at + 1]
        del args[at:at + 2]
    dtwire, campaign, work = args
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "out")
    run = subprocess.run([dtwire, "campaign", campaign, "-o", out], capture_output=True, text=True, timeout=300)
    print(run.stderr + run.stdout)
    if run.returncode != 0:
        sys.exit("the fixture campaign failed (exit %d)" % run.returncode)
    report = os.path.abspath(os.path.join(out, "report.html"))
    url = "file://" + report

    dumped = chromium("--virtual-time-budget=10000", "--dump-dom", url, profile=os.path.join(work, "profile"))
    if dumped.returncode != 0:
        sys.exit("chromium failed (exit %d): %s" % (dumped.returncode, dumped.stderr[-2000:]))
    dom = Dom()
    dom.feed(dumped.stdout)
    failures = []
    images = dom.body.get("data-images", "")
    match = re.fullmatch(r"(\d+)/(\d+)", images)
    if not match:
        failures.append("the page's load script did not run (body data-images=%r)" % images)
    else:
        loaded, total = int(match.group(1)), int(match.group(2))
        if total == 0 or total != dom.images:
            failures.append("expected the fixture's figures as images, found %s (DOM has %d)" % (images, dom.images))
        if loaded != total:
            failures.append("%d of %d images did not load" % (total - loaded, total))
    if dom.body.get("data-errors") != "0":
        failures.append("script errors on the page: data-errors=%r" % dom.body.get("data-errors"))
    if dom.summary_tables == 0:
        failures.append("no table in the summary section")
    for heading in ("calibrated-parameter-sets", "gap-verdicts", "what-to-distrust"):
        if heading not in dom.summary_headings:
            failures.append("summary lacks the section #%s (has %s)" % (heading, dom.summary_headings))
    if screenshot:
        shot = chromium("--window-size=1280,1000", "--hide-scrollbars", "--screenshot=" + os.path.abspath(screenshot),
                        url, profile=os.path.join(work, "profile"))
        if shot.returncode != 0 or not os.path.exists(screenshot):
            failures.append("screenshot failed: " + shot.stderr[-500:])
    for failure in failures:
        print("FAIL: " + failure)
    if failures:
        sys.exit(1)
    print("report.html renders: %s images loaded, %d summary tables, summary sections %s"
          % (images, dom.summary_tables, ", ".join(dom.summary_headings)))


if __name__ == "__main__":
    main()
