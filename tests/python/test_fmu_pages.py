"""Each FMU's documentation/index.html rendered in headless Chromium (Debian's `chromium`,
which scripts/test.sh installs when it is missing): no console message of the page's own, no
broken image, and a plot for every output of the reference results.

The page is copied with a small checking script appended that runs after `load`: it reports
every image that failed to load and the number of inline SVG plots through console.log, and
errors of the page's own scripts reach the console as well. Chromium prints console messages
to stderr as `CONSOLE` lines (--enable-logging=stderr), which the test reads.
"""

import re
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest

FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--enable-logging=stderr",
    "--v=0",
    "--virtual-time-budget=5000",
    "--dump-dom",
]

CHECK = """<script>
window.addEventListener("load", () => {
  const broken = [...document.images]
    .filter(i => !i.complete || i.naturalWidth === 0).map(i => i.src);
  console.log("page-check: broken=" + JSON.stringify(broken)
    + " svgs=" + document.querySelectorAll("svg").length);
});
</script>"""


def render(html: Path, profile: Path, check: str = CHECK):
    """Console lines of `html` rendered headless (with the script `check` appended) and the
    DOM after the scripts ran."""
    chromium = shutil.which("chromium")
    if chromium is None:
        pytest.fail(
            "chromium not found: scripts/test.sh installs it (apt-get install chromium)",
            pytrace=False,
        )
    checked = html.with_name("checked_" + html.name)
    checked.write_text(html.read_text().replace("</body>", check + "</body>"))
    run = subprocess.run(
        [chromium, *FLAGS, f"--user-data-dir={profile}", checked.as_uri()],
        capture_output=True,
        text=True,
        timeout=120,
    )
    console = [line for line in run.stderr.splitlines() if ":CONSOLE" in line]
    return console, run.stdout


@pytest.mark.parametrize(
    "name", ["WoundOpening", "WoundOpening-fmi3", "PurseString", "PurseString-fmi3"]
)
def test_fmu_page_renders_without_errors(tmp_path, name):
    fmu = Path(__file__).resolve().parents[2] / "target" / "fmu" / f"{name}.fmu"
    assert fmu.is_file(), f"{fmu} missing: cargo run --release -- fmu"
    with zipfile.ZipFile(fmu) as z:
        z.extractall(tmp_path / "fmu")
    console, dom = render(tmp_path / "fmu" / "documentation" / "index.html", tmp_path / "profile")
    checks = [line for line in console if "page-check:" in line]
    others = [line for line in console if "page-check:" not in line]
    assert others == [], "console messages:\n" + "\n".join(others)
    assert len(checks) == 1, console
    found = re.search(r"broken=(\[.*?\]) svgs=(\d+)", checks[0])
    assert found and found.group(1) == "[]", checks[0]
    with zipfile.ZipFile(fmu) as z:
        outputs = (
            z.read("extra/org.fmi-standard.fmi-ls-ref/" + name.split("-")[0] + "_out.csv")
            .decode()
            .splitlines()[0]
        )
        # One plot per output, and one of the paper's cases where the archive carries them.
        cases = any(n.endswith("_ref.csv") for n in z.namelist())
    assert int(found.group(2)) == len(outputs.split(",")) - 1 + cases, (checks[0], outputs)
    assert "Usage with fmpy" in dom


def test_the_check_finds_a_broken_image_and_a_console_error(tmp_path):
    """The test above can fail: a page with a missing image and a script error is caught."""
    bad = tmp_path / "bad.html"
    bad.write_text(
        '<html><body><img src="missing.png"><script>console.error("boom")</script></body></html>'
    )
    console, _ = render(bad, tmp_path / "profile")
    assert any('"boom"' in line for line in console), console
    assert any("missing.png" in line for line in console if "page-check:" in line), console
