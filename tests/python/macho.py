"""What the tests read from a macOS library without a Mac: its Mach-O headers (through the
PyPI package macholib), the symbols dyld exports (the export trie, read here) and whether
the ad-hoc code signature matches the code (the page hashes, recomputed here).

A universal file gives one `Slice` per architecture.
"""

from __future__ import annotations

import hashlib
import struct
from dataclasses import dataclass
from pathlib import Path

from macholib import mach_o
from macholib.MachO import MachO

ARCHS = {0x01000007: "x86_64", 0x0100000C: "arm64"}
# Code signing blobs (big-endian; Apple's cs_blobs.h): the embedded signature holds a code
# directory whose hash slots are the hashes of the file's pages up to codeLimit.
CSMAGIC_EMBEDDED_SIGNATURE = 0xFADE0CC0
CSMAGIC_CODEDIRECTORY = 0xFADE0C02
CS_ADHOC = 0x2
HASH_SHA256 = 2


@dataclass
class Slice:
    arch: str
    filetype: int
    install_name: str | None
    dylibs: list[str]
    minimum_os: tuple[int, int] | None
    exports: list[str]
    local_symbols: int
    signature: dict | None


def _uleb(data: bytes, p: int) -> tuple[int, int]:
    value = shift = 0
    while True:
        byte = data[p]
        p += 1
        value |= (byte & 0x7F) << shift
        shift += 7
        if byte < 0x80:
            return value, p


def export_trie(data: bytes) -> list[str]:
    """The names of dyld's export trie: each node has its terminal info (size, then bytes:
    the name ending here is exported when the size is not 0), then its children (count,
    then per child its edge label, NUL-terminated, and its node's offset)."""
    names, stack = [], [(0, b"")]
    while stack and data:
        offset, prefix = stack.pop()
        size, p = _uleb(data, offset)
        if size:
            names.append(prefix.decode())
        p += size
        count, p = data[p], p + 1
        for _ in range(count):
            end = data.index(b"\0", p)
            label, p = data[p:end], end + 1
            child, p = _uleb(data, p)
            stack.append((child, prefix + label))
    return sorted(names)


def _version(v: int) -> tuple[int, int]:
    return v >> 16, (v >> 8) & 0xFF


def code_signature(image: bytes, dataoff: int, datasize: int) -> dict:
    """The code directory of an embedded signature, and whether every page hash matches."""
    blob = image[dataoff : dataoff + datasize]
    magic, _, count = struct.unpack_from(">III", blob)
    assert magic == CSMAGIC_EMBEDDED_SIGNATURE, hex(magic)
    for k in range(count):
        _, offset = struct.unpack_from(">II", blob, 12 + 8 * k)
        if struct.unpack_from(">I", blob, offset)[0] != CSMAGIC_CODEDIRECTORY:
            continue
        cd = blob[offset:]
        (_, _, _, flags, hash_offset, ident_offset, _, slots, limit, size, kind, _, page) = (
            struct.unpack_from(">IIIIIIIIIBBBB", cd)
        )
        page_size = 1 << page
        hashes_ok = kind == HASH_SHA256 and all(
            hashlib.sha256(image[p * page_size : min((p + 1) * page_size, limit)]).digest()
            == cd[hash_offset + size * p : hash_offset + size * (p + 1)]
            for p in range(slots)
        )
        ident = cd[ident_offset : cd.index(b"\0", ident_offset)].decode()
        return {
            "adhoc": bool(flags & CS_ADHOC),
            "identifier": ident,
            "pages": slots,
            "covers_code": limit == dataoff and slots * page_size >= limit,
            "hashes_ok": hashes_ok,
        }
    raise AssertionError("no code directory in the signature")


def read(path: Path) -> list[Slice]:
    data = path.read_bytes()
    slices = []
    for header in MachO(str(path)).headers:
        image = data[header.offset : header.offset + header.size]
        s = Slice(
            ARCHS.get(header.header.cputype, "?"),
            header.header.filetype,
            None,
            [],
            None,
            [],
            0,
            None,
        )
        for lc, cmd, payload in header.commands:
            name = mach_o.LC_NAMES.get(lc.cmd)
            if name == "LC_ID_DYLIB":
                s.install_name = payload.rstrip(b"\0").decode()
            elif name in ("LC_LOAD_DYLIB", "LC_LOAD_WEAK_DYLIB", "LC_REEXPORT_DYLIB"):
                s.dylibs.append(payload.rstrip(b"\0").decode())
            elif name == "LC_BUILD_VERSION":
                s.minimum_os = _version(cmd.minos)
            elif name == "LC_VERSION_MIN_MACOSX":
                s.minimum_os = _version(cmd.version)
            elif name == "LC_DYLD_INFO_ONLY" and cmd.export_size:
                s.exports = export_trie(image[cmd.export_off : cmd.export_off + cmd.export_size])
            elif name == "LC_DYLD_EXPORTS_TRIE":
                s.exports = export_trie(image[cmd.dataoff : cmd.dataoff + cmd.datasize])
            elif name == "LC_DYSYMTAB":
                s.local_symbols = cmd.nlocalsym
            elif name == "LC_CODE_SIGNATURE":
                s.signature = code_signature(image, cmd.dataoff, cmd.datasize)
        slices.append(s)
    return slices
