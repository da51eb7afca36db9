#!/usr/bin/env python3
"""How fast a scan report opens, in headless Chromium: one command, a median.

    .venv/bin/python scripts/report_timing.py results/paper            # makes the report, opens it 5 times
    .venv/bin/python scripts/report_timing.py FILE.html --runs 7 --json out.json

Each load starts a fresh headless Chromium (Debian's `chromium` and
`chromedriver`, as the browser test: SE_OFFLINE, nothing downloaded), so no
load reuses another's compiled code, and reads the Performance API marks the
page sets (crates/rtw-py/python/rtw/report_assets/report.js), in ms from
navigation start:

- `rtw:first-view`: the header, the summary table and the first plot (the
  gait map) drawn and painted (or the first contentful paint, if later);
- `rtw:ready`: every plot drawn;

and the steps between (`rtw:inflated`, `rtw:plotly`, ...), and the browser's
first contentful paint. It prints each load, the median of each, and the load
average of the machine before each load (the times depend on it: the browser
draws WebGL in software, SwiftShader, on the CPU the machine has left). It
also sums the CPU time all the browser's processes spent from before the
navigation to the end (psutil): on a busy machine, what the whole page costs.

The browser test (crates/rtw-py/tests/test_report_browser.py) opens the page
with `open_chromium` and `wait_ready` from here.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# The window the browser test and the screenshot use.
WINDOW = "1400,2400"


def open_chromium(window: str = WINDOW):
    """Headless Chromium through the system's chromedriver, logging the console."""
    os.environ["SE_OFFLINE"] = "true"  # Selenium Manager must not download a driver or a browser
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    chromium, driver = shutil.which("chromium"), shutil.which("chromedriver")
    if chromium is None or driver is None:
        raise SystemExit("needs chromium and chromium-driver (Debian packages: apt-get install -y chromium chromium-driver)")
    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", f"--window-size={window}",
                "--enable-unsafe-swiftshader"):
        opts.add_argument(arg)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    browser = webdriver.Chrome(service=Service(driver), options=opts)
    # A 10^5-row page keeps the page's thread busy for longer than Selenium's
    # default 30 s on a loaded machine; a query waits for it.
    browser.set_script_timeout(300)
    return browser


def browser_cpu(driver) -> float:
    """CPU seconds (user + system) spent so far by the browser's processes (chromedriver's children)."""
    import psutil

    total = 0.0
    for p in psutil.Process(driver.service.process.pid).children(recursive=True):
        try:
            t = p.cpu_times()
            total += t.user + t.system
        except psutil.NoSuchProcess:
            pass
    return total


def wait_ready(driver, timeout: float = 300.0) -> dict:
    """Waits until the page has drawn every plot; returns its marks (ms from navigation start)."""
    started = time.monotonic()
    while not driver.execute_script("return !!(window.rtwReport && window.rtwReport.ready)"):
        status = driver.execute_script("const s = document.getElementById('status'); return s ? s.textContent : ''")
        if "could not" in status:
            raise RuntimeError(status)
        if time.monotonic() - started > timeout:
            raise TimeoutError(f"the report was not drawn within {timeout:.0f} s")
        time.sleep(0.05)
    return driver.execute_script(
        "const m = {}; performance.getEntriesByType('mark').filter(e => e.name.startsWith('rtw:'))"
        ".forEach(e => { m[e.name.slice(4)] = e.startTime; });"
        "const fcp = performance.getEntriesByName('first-contentful-paint')[0];"
        "if (fcp) m['first-contentful-paint'] = fcp.startTime; return m;")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("target", help="a report (.html), or a scan directory whose report is made first")
    ap.add_argument("--runs", type=int, default=5, help="loads, each in a fresh browser (default 5)")
    ap.add_argument("--json", help="write every load's marks and the medians here")
    args = ap.parse_args()
    if args.runs < 1:
        ap.error(f"--runs: {args.runs} is invalid: must be at least 1")
    target = Path(args.target)
    if target.suffix == ".html":
        page = target
    else:
        out = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "report-timing"
        out.mkdir(parents=True, exist_ok=True)
        page = out / f"{target.resolve().name}.html"
        subprocess.run([sys.executable, "-m", "rtw", "report", str(target), "--out", str(page), "--force"],
                       check=True, cwd=ROOT)
    print(f"{page}: {page.stat().st_size / 1e6:.2f} MB")
    loads = []
    for k in range(args.runs):
        load = os.getloadavg()[0]
        driver = open_chromium()
        try:
            cpu = browser_cpu(driver)
            driver.get(page.resolve().as_uri())
            marks = wait_ready(driver)
            cpu = browser_cpu(driver) - cpu
            severe = [e["message"] for e in driver.get_log("browser") if e["level"] == "SEVERE"]
        finally:
            driver.quit()
        if severe:
            raise SystemExit(f"console errors: {severe}")
        # The page's mark is set once the frame with the gait map is painted on
        # the page's thread; the screen shows it a little later. The browser's
        # first contentful paint is a presentation time: a first view before it
        # is counted at it (on a busy machine the compositor can lag behind).
        marks["first-view"] = max(marks["first-view"], marks.get("first-contentful-paint", 0.0))
        marks["load average"] = load
        marks["cpu"] = 1000 * cpu
        loads.append(marks)
        steps = ", ".join(f"{n} {v:.0f}" for n, v in sorted(marks.items(), key=lambda kv: kv[1])
                          if n not in ("load average", "cpu"))
        print(f"load {k + 1}: first view {marks['first-view']:.0f} ms, ready {marks['ready']:.0f} ms, the browser's "
              f"CPU time {marks['cpu']:.0f} ms (load average {load:.1f}; {steps})")
    names = sorted({n for m in loads for n in m}, key=lambda n: statistics.median(m.get(n, 0) for m in loads))
    median = {n: statistics.median(m[n] for m in loads if n in m) for n in names}
    print(f"median of {len(loads)}: first view {median['first-view']:.0f} ms, everything drawn "
          f"{median['ready']:.0f} ms; the browser's CPU time "
          f"{median['cpu']:.0f} ms; load average {median['load average']:.1f} "
          f"({min(m['load average'] for m in loads):.1f}–{max(m['load average'] for m in loads):.1f}) on "
          f"{os.cpu_count()} CPUs")
    if args.json:
        Path(args.json).write_text(json.dumps({"page": str(page), "bytes": page.stat().st_size,
                                               "loads": loads, "median": median}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
