"""Print the report to PDF with headless Chromium (the same page the browser shows).

Chromium is looked up, in order: the ``chromium`` argument, the environment variable
``ROLLSPRING_CHROMIUM``, then ``chromium``, ``chromium-browser``, ``google-chrome``,
``google-chrome-stable`` on ``PATH``. Without it, :class:`ReportError` says what to install.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from rollspring.outputs.atomic import atomic_write_bytes
from rollspring.outputs.report._html import ReportError

__all__ = ["CHROMIUM_ENV", "find_chromium", "html_to_pdf"]

#: Environment variable naming the Chromium executable used for ``--format pdf``.
CHROMIUM_ENV = "ROLLSPRING_CHROMIUM"
_NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
_INSTALL = "install chromium (Debian/Ubuntu: apt-get install chromium)"


def find_chromium(chromium: str | os.PathLike[str] | None = None) -> str:
    """Path of the Chromium executable; :class:`ReportError` naming what to install if none."""
    if chromium is None and os.environ.get(CHROMIUM_ENV):
        chromium = os.environ[CHROMIUM_ENV]
        source = f"{CHROMIUM_ENV}={chromium}"
    else:
        source = str(chromium) if chromium is not None else ""
    if chromium is not None:
        found = shutil.which(str(chromium))
        if found is None:
            raise ReportError(
                f"--format pdf needs Chromium, not found at {source}: {_INSTALL} "
                f"or set {CHROMIUM_ENV} to its path"
            )
        return found
    for name in _NAMES:
        found = shutil.which(name)
        if found is not None:
            return found
    raise ReportError(
        f"--format pdf needs Chromium, none on PATH: {_INSTALL} or set {CHROMIUM_ENV} to its path"
    )


def html_to_pdf(
    html: str,
    path: str | os.PathLike[str],
    *,
    chromium: str | os.PathLike[str] | None = None,
    timeout: float = 120.0,
) -> Path:
    """Print ``html`` to a PDF file at ``path`` (written atomically) with headless Chromium.

    The page is loaded from a private temporary folder with a throw-away browser profile;
    the browser is started without networking features (the page makes no requests anyway: its
    Content-Security-Policy forbids them).
    """
    executable = find_chromium(chromium)
    target = Path(path)
    with tempfile.TemporaryDirectory(prefix="rollspring-pdf-") as folder:
        page = Path(folder) / "report.html"
        page.write_text(html, encoding="utf-8")
        printed = Path(folder) / "report.pdf"
        command = [
            executable,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-extensions",
            "--no-default-browser-check",
            "--hide-scrollbars",
            f"--user-data-dir={Path(folder) / 'profile'}",
            "--no-pdf-header-footer",
            "--run-all-compositor-stages-before-draw",
            "--virtual-time-budget=2000",
            f"--print-to-pdf={printed}",
            page.as_uri(),
        ]
        try:
            result = subprocess.run(
                command,
                capture_output=True,
                text=True,
                timeout=timeout,
                check=False,
                stdin=subprocess.DEVNULL,
            )
        except subprocess.TimeoutExpired:
            raise ReportError(
                f"--format pdf: Chromium ({executable}) did not finish printing "
                f"within {timeout:g} s"
            ) from None
        except OSError as exc:
            raise ReportError(
                f"--format pdf: cannot run Chromium ({executable}): {exc.strerror or exc}"
            ) from None
        data = printed.read_bytes() if printed.exists() else b""
        if not data.startswith(b"%PDF"):
            lines = [
                line
                for line in (result.stderr or "").splitlines()
                if line.strip() and "dbus" not in line
            ]
            reason = lines[-1].strip() if lines else f"exit code {result.returncode}"
            raise ReportError(f"--format pdf: Chromium ({executable}) printed no PDF: {reason}")
    try:
        atomic_write_bytes(target, data)
    except OSError as exc:
        raise ReportError(f"{target}: cannot write ({exc.strerror or exc})") from None
    return target
