# SPDX-License-Identifier: MIT
"""The data arrays of the VTK XML files nmm writes (.vtu, .vtp; docs/output.md), read with
the Python standard library, for scripts on machines without VTK's Python module
(examples/17_hertz_contact/hertz_pressure.py, bench/stress.py).

nmm writes binary data compressed by VTK's LZ4 compressor: per array a header of UInt32 or
UInt64 words (number of blocks, block size, size of the last block, then the compressed size
of each block) and the LZ4 blocks, decoded here. Since 2026-12-01 each array's data is
base64 text inside its DataArray element (format="binary": well-formed XML that ParaView
5.11 reads with Debian 12's expat, docs/output.md): the header is encoded on its own, then
the compressed blocks together, each ending with its own padding. Files written before then
hold the same bytes raw in an AppendedData element (format="appended", encoding="raw", an
array's offset counting bytes after the "_" that starts the data); those are read too, and
base64 appended data as well.
"""

import base64
import re
import struct

_TYPES = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i", "Int8": "b",
          "UInt64": "Q", "UInt32": "I", "UInt8": "B"}
_SECTION = r"<(Points|PointData|CellData|Cells|Verts|Lines|Polys|Strips|FieldData)[\s>]"


def lz4_block(source, size):
    """Decodes one LZ4 block (the format of the lz4 library's LZ4_compress_default)."""
    out = bytearray()
    i = 0

    def length(nibble):
        """A length from its token nibble: 15 goes on in bytes until one below 255."""
        nonlocal i
        if nibble == 15:
            while True:
                extra = source[i]
                i += 1
                nibble += extra
                if extra != 255:
                    break
        return nibble

    while i < len(source):
        token = source[i]
        i += 1
        literals = length(token >> 4)
        out += source[i:i + literals]
        i += literals
        if i >= len(source):  # the last sequence has literals only
            break
        offset = source[i] | (source[i + 1] << 8)
        i += 2
        match = length(token & 15) + 4
        start = len(out) - offset
        if offset >= match:
            out += out[start:start + match]
        else:
            for k in range(match):  # byte by byte: the match overlaps what it copies
                out.append(out[start + k])
    if len(out) != size:
        raise ValueError("LZ4 block decoded to %d bytes, expected %d" % (len(out), size))
    return bytes(out)


def read_arrays(path, names=None):
    """The data arrays of @p path by name, each a flat list of numbers (the components of a
    tuple one after the other; a String array a list of str); the point coordinates as
    "Points". Only @p names when given (a ValueError names the ones missing). A name the file
    repeats (a .vtp's connectivity of each cell kind) keeps its first array."""
    with open(path, "rb") as f:
        data = f.read()
    match = re.search(rb'<AppendedData encoding="(raw|base64)">\s*_', data)
    appended = data[match.end():] if match else b""
    appended_encoded = bool(match) and match.group(1) == b"base64"
    text = (data[:match.start()] if match else data).decode("latin-1")
    if 'compressor="vtkLZ4DataCompressor"' not in text:
        raise ValueError("%s is not LZ4-compressed (nmm's files are)" % path)
    header = "Q" if 'header_type="UInt64"' in text else "I"
    width = struct.calcsize(header)

    def take(source, encoded, start, size):
        """@p size bytes of data at @p start of @p source, and where the data after them
        starts: in base64 a stream of its own, 4 characters for every 3 bytes or part."""
        if not encoded:
            return source[start:start + size], start + size
        length = 4 * ((size + 2) // 3)
        return base64.b64decode(source[start:start + length])[:size], start + length

    arrays = {}
    section = None
    for element in re.finditer(_SECTION + r"|<(Data)?Array ([^>]*?)(/?)>", text):
        if element.group(1):
            section = element.group(1)
            continue
        attributes = dict(re.findall(r'(\w+)="([^"]*)"', element.group(3)))
        name = "Points" if section == "Points" else attributes.get("Name")
        if name in arrays or (names is not None and name not in names):
            continue
        if attributes.get("format") == "appended":
            source, encoded, offset = appended, appended_encoded, int(attributes["offset"])
        elif attributes.get("format") == "binary":  # base64 text inside the element
            end = text.index("</" + ("Data" if element.group(2) else "") + "Array>",
                             element.end())
            source = "".join(text[element.end():end].split()).encode("ascii")
            encoded, offset = True, 0
        else:
            raise ValueError("%s: array %s is %s, not nmm's binary data" %
                             (path, name, attributes.get("format")))
        # The header's first three words give the number of blocks, hence its length.
        blocks = struct.unpack_from("<" + header, take(source, encoded, offset, width)[0])[0]
        words, position = take(source, encoded, offset, (3 + blocks) * width)
        _, block_size, last_size, *sizes = struct.unpack("<%d%s" % (3 + blocks, header), words)
        compressed, _ = take(source, encoded, position, sum(sizes))
        chunks = []
        start = 0
        for k, length in enumerate(sizes):
            size = last_size if k == blocks - 1 and last_size else block_size
            chunks.append(lz4_block(compressed[start:start + length], size))
            start += length
        blob = b"".join(chunks)
        if attributes["type"] == "String":  # each value ends with a NUL byte
            arrays[name] = [v.decode("utf-8") for v in blob.split(b"\0")[:-1]]
            continue
        code = _TYPES[attributes["type"]]
        arrays[name] = list(struct.unpack("<%d%s" % (len(blob) // struct.calcsize(code), code),
                                          blob))
    missing = set(names or ()) - set(arrays)
    if missing:
        raise ValueError("%s has no array %s" % (path, ", ".join(sorted(missing))))
    return arrays
