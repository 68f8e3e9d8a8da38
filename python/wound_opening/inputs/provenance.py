"""What was read from a lab's raw files: each file's SHA-256 (of the bytes read, not of a
converted copy), what program wrote it, how many rows or vectors it held, how many were
dropped and why, and how many were used."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field


@dataclass(frozen=True)
class RawFile:
    """One raw file read. `counts`: name -> number, in the order read (e.g. rows, before the
    cut, tracking failed, used); `notes`: sentences for the report and the command line."""

    path: str
    sha256: str
    kind: str
    counts: dict = field(default_factory=dict)
    notes: tuple = ()

    def line(self) -> str:
        counts = ", ".join(f"{k} {v}" for k, v in self.counts.items())
        return f"{self.path} ({self.kind}): {counts}"


def sha256_bytes(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def read_bytes(path: str, error) -> bytes:
    """The file's bytes, or `error` (an InputError class) naming the file."""
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as e:
        raise error(f"{path}: cannot read the file ({e.strerror})") from None


def decode(path: str, data: bytes, error) -> list[str]:
    """The text lines of `data` (UTF-8, a byte-order mark dropped, CRLF or LF)."""
    try:
        return data.decode("utf-8-sig").splitlines()
    except UnicodeDecodeError:
        raise error(f"{path}: not a UTF-8 text file") from None


def notes_of(*series) -> list[str]:
    """Every note of the raw files behind the given series (None skipped)."""
    return [n for s in series if s is not None for f in getattr(s, "files", ()) for n in f.notes]
