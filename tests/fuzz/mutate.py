"""Seeded mutations of the fuzz test's inputs: scenes (YAML), Gmsh files (MSH 2.2 / 4.1, ASCII and
binary) and OpenFOAM polyMesh files. Every function takes a random.Random, so one integer seed gives the
same mutant on every machine (Python's Random is specified and stable across versions for these calls),
and returns the mutated bytes plus a one-line description that the driver prints and stores.

Mutations are aimed at what readers get wrong: counts and indices that are 0, negative, one off, beyond
int32/int64 or absurdly large; numbers that are nan, inf, out of double range or denormal; wrong types;
broken structure (truncation, deleted or duplicated lines, unbalanced brackets, renamed section headers);
bytes that are not UTF-8. Structure-aware mutations pick their target from the text itself (regular
expressions over tokens), so the seeds can change without touching this file."""

import re
import struct

import yaml

# ---------------------------------------------------------------------------------------------------------
# Value pools

# Numbers as they would be written in a text file: edge cases of parsing (1e400 overflows a double,
# 1e-320 is denormal) and of integer conversion (2^31, 2^32+1, 2^63, -2^63-1, 20 digits).
SPECIAL_NUMBERS = [
    "0", "-1", "1", "-0", "0.0", "1.5", "-1e-300", "1e-320", "4.9e-324", "1e308", "1e400", "-1e400",
    "nan", "NaN", ".nan", "inf", "-inf", ".inf", "-.inf", "2147483647", "2147483648", "-2147483649",
    "4294967297", "9223372036854775807", "9223372036854775808", "-9223372036854775809",
    "99999999999999999999999", "0x10", "1e5", "1_000", "+5", "0.", ".5", "1e", "--1", "1e+",
]
# Values of the wrong type for a YAML scalar slot.
WRONG_TYPES = [
    "abc", "''", '""', "~", "null", "true", "false", "[]", "{}", "[1, 2, 3]", "{a: 1}", "[[1, 2], [3]]",
    "!!binary aGVsbG8=", "!!str 5", "!custom 1", "*undefined_alias", "&anchor 1", "2001-12-14", "'5'",
    "|\n  literal", ">-", "- 1", "? x", "@", "`", "%", "'unterminated", '"\\x"', '"\\uD800"',
]
# Byte sequences that are not valid UTF-8 (lone continuation, overlong, surrogate, truncated, 0xFF).
NON_UTF8 = [b"\xff", b"\xfe\xff", b"\x80", b"\xc3\x28", b"\xc0\xaf", b"\xed\xa0\x80", b"\xf4\x90\x80\x80",
            b"\xe2\x82", b"\xf0\x9f\x98"]
JUNK = [b"\x00", b"\t", b"\r", b"\r\n", b":", b"{", b"}", b"[", b"]", b",", b"#", b"&", b"*", b"!", b"|",
        b">", b"'", b'"', b"%", b"@", b"-", b"?", b"\\", b"$", b"(", b")", b";", b"\x1b", b"\x7f", b"\xef\xbb\xbf"]


def special_integer(rng, old=None):
    """An integer edge case; near the old value (off by one) when there is one."""
    pool = [0, -1, 1, 2, 3, 2**31 - 1, 2**31, 2**32 - 1, 2**32, 2**32 + 1, 2**63 - 1, 2**63, 2**64 - 1,
            -(2**31), -(2**63), 10**9, 10**12, 10**30]
    if old is not None:
        pool += [old + 1, old - 1, old * 2, -old, old + 2**32]
    return rng.choice(pool)


def pick(rng, seq):
    return seq[rng.randrange(len(seq))]


# ---------------------------------------------------------------------------------------------------------
# Byte-level mutations (any kind of file)

def byte_flip(rng, data):
    if not data:
        return b"\x00", "byte_flip on empty input: wrote one NUL"
    i = rng.randrange(len(data))
    bit = rng.randrange(8)
    out = bytearray(data)
    out[i] ^= 1 << bit
    return bytes(out), f"byte_flip offset {i} bit {bit}"


def random_bytes(rng, n):
    return bytes(rng.randrange(256) for _ in range(n))


def insert_bytes(rng, data):
    i = rng.randrange(len(data) + 1)
    kind = rng.randrange(3)
    if kind == 0:
        junk = random_bytes(rng, rng.randint(1, 8))
    elif kind == 1:
        junk = pick(rng, JUNK)
    else:
        junk = pick(rng, NON_UTF8)
    return data[:i] + junk + data[i:], f"insert_bytes offset {i} {junk!r}"


def delete_bytes(rng, data):
    if not data:
        return data, "delete_bytes on empty input"
    i = rng.randrange(len(data))
    n = rng.randint(1, min(16, len(data) - i))
    return data[:i] + data[i + n:], f"delete_bytes offset {i} length {n}"


def truncate(rng, data):
    i = rng.randrange(len(data) + 1)
    return data[:i], f"truncate at {i} of {len(data)} bytes"


def non_utf8(rng, data):
    i = rng.randrange(len(data) + 1)
    seq = pick(rng, NON_UTF8)
    return data[:i] + seq + data[i:], f"non_utf8 {seq!r} at offset {i}"


# ---------------------------------------------------------------------------------------------------------
# Line-level mutations (text files)

def _lines(data):
    return data.splitlines(keepends=True)


def delete_line(rng, data):
    lines = _lines(data)
    if not lines:
        return data, "delete_line on empty input"
    i = rng.randrange(len(lines))
    return b"".join(lines[:i] + lines[i + 1:]), f"delete_line {i + 1}"


def duplicate_line(rng, data):
    lines = _lines(data)
    if not lines:
        return data, "duplicate_line on empty input"
    i = rng.randrange(len(lines))
    j = rng.randrange(len(lines) + 1)
    line = lines[i] if lines[i].endswith(b"\n") else lines[i] + b"\n"
    return b"".join(lines[:j] + [line] + lines[j:]), f"duplicate_line {i + 1} to before line {j + 1}"


def swap_lines(rng, data):
    lines = _lines(data)
    if len(lines) < 2:
        return data, "swap_lines on < 2 lines"
    i, j = rng.sample(range(len(lines)), 2)
    lines[i], lines[j] = lines[j], lines[i]
    return b"".join(lines), f"swap_lines {i + 1} {j + 1}"


# ---------------------------------------------------------------------------------------------------------
# Token-level helpers

NUMBER_RE = re.compile(rb"(?<![\w.])[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)(?![\w.])")
INTEGER_RE = re.compile(rb"(?<![\w.\-+])-?\d+(?![\w.])")


def _replace_match(data, m, new):
    return data[:m.start()] + new + data[m.end():]


def replace_number(rng, data, pool=None):
    """Replaces one number token by a special value (text form)."""
    matches = list(NUMBER_RE.finditer(data))
    if not matches:
        return insert_bytes(rng, data)
    m = pick(rng, matches)
    new = pick(rng, pool or SPECIAL_NUMBERS).encode()
    line = data.count(b"\n", 0, m.start()) + 1
    return _replace_match(data, m, new), f"number {m.group().decode()!r} -> {new.decode()!r} (line {line})"


def replace_integer(rng, data, matches=None):
    """Replaces one integer token by an integer edge case (counts, tags, indices)."""
    matches = matches if matches is not None else list(INTEGER_RE.finditer(data))
    if not matches:
        return replace_number(rng, data)
    m = pick(rng, matches)
    old = int(m.group())
    new = str(special_integer(rng, old)).encode()
    line = data.count(b"\n", 0, m.start()) + 1
    return _replace_match(data, m, new), f"integer {old} -> {new.decode()} (line {line})"


# ---------------------------------------------------------------------------------------------------------
# Scenes (YAML)

KEY_VALUE_RE = re.compile(rb"(?P<key>[A-Za-z_][\w]*)[ \t]*:[ \t]+(?P<val>[^,{}\[\]\n#]+?)[ \t]*(?=[,}\]\n#]|$)")
KEY_RE = re.compile(rb"(?P<key>[A-Za-z_][\w]*)[ \t]*:(?=[ \t\n])")


def _yaml_paths(node, prefix=(), seen=None):
    """Every path in a parsed YAML tree (dict keys and list indices), leaves and inner nodes. A node
    reached again through an alias is listed once: a "billion laughs" tree stays small."""
    seen = set() if seen is None else seen
    out = []
    if isinstance(node, (dict, list)):
        if id(node) in seen:
            return out
        seen.add(id(node))
    if isinstance(node, dict):
        for k, v in node.items():
            out.append((prefix + (k,), v))
            out.extend(_yaml_paths(v, prefix + (k,), seen))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.append((prefix + (i,), v))
            out.extend(_yaml_paths(v, prefix + (i,), seen))
    return out


def _get_parent(tree, path):
    node = tree
    for p in path[:-1]:
        node = node[p]
    return node


def _dump(tree):
    return yaml.safe_dump(tree, default_flow_style=None, sort_keys=False, width=100).encode()


def _path_text(path):
    return ".".join(str(p) for p in path)


def scene_wrong_type(rng, data):
    matches = list(KEY_VALUE_RE.finditer(data))
    if not matches:
        return insert_bytes(rng, data)
    m = pick(rng, matches)
    new = pick(rng, WRONG_TYPES).encode()
    line = data.count(b"\n", 0, m.start()) + 1
    out = data[:m.start("val")] + new + data[m.end("val"):]
    return out, f"value of {m.group('key').decode()!r} (line {line}) -> {new.decode()!r}"


def scene_duplicate_key(rng, data):
    """Writes a key twice in the same mapping: `young: 1, young: 2` (flow) or a repeated block line."""
    matches = list(KEY_VALUE_RE.finditer(data))
    if not matches:
        return duplicate_line(rng, data)
    m = pick(rng, matches)
    line = data.count(b"\n", 0, m.start()) + 1
    val = pick(rng, [m.group("val"), pick(rng, SPECIAL_NUMBERS).encode()])
    dup = m.group("key") + b": " + val
    # Inside a flow mapping a comma separates entries; in block style the copy goes on its own line with
    # the same indentation.
    line_start = data.rfind(b"\n", 0, m.start()) + 1
    prefix = data[line_start:m.start()]
    if b"{" in prefix or data[m.end():m.end() + 1] in (b",", b"}"):
        out = data[:m.end()] + b", " + dup + data[m.end():]
    else:
        indent = re.match(rb"[ \t-]*", prefix).group().replace(b"-", b" ")
        eol = data.find(b"\n", m.end())
        eol = len(data) if eol < 0 else eol
        out = data[:eol] + b"\n" + indent + dup + data[eol:]
    return out, f"duplicate key {m.group('key').decode()!r} (line {line}) with value {val.decode()!r}"


def scene_delete_key(rng, data):
    tree = yaml.safe_load(data)
    paths = [p for p, _ in _yaml_paths(tree)]
    if not paths:
        return truncate(rng, data)
    path = pick(rng, paths)
    parent = _get_parent(tree, path)
    del parent[path[-1]]
    return _dump(tree), f"delete {_path_text(path)} (rewritten by yaml.safe_dump)"


def scene_swap_values(rng, data):
    tree = yaml.safe_load(data)
    paths = [p for p, _ in _yaml_paths(tree)]
    if len(paths) < 2:
        return scene_delete_key(rng, data)
    a, b = rng.sample(paths, 2)
    # A path inside the other would make a cycle: swap a leaf with something else instead.
    if a[:len(b)] == b or b[:len(a)] == a:
        return scene_delete_key(rng, data)
    pa, pb = _get_parent(tree, a), _get_parent(tree, b)
    pa[a[-1]], pb[b[-1]] = pb[b[-1]], pa[a[-1]]
    return _dump(tree), f"swap {_path_text(a)} <-> {_path_text(b)} (rewritten by yaml.safe_dump)"


def scene_rename_key(rng, data):
    matches = list(KEY_RE.finditer(data))
    if not matches:
        return insert_bytes(rng, data)
    m = pick(rng, matches)
    key = m.group("key")
    new = pick(rng, [key[:-1] or b"x", key + key[-1:], key.upper(), b"", b"'" + key + b" '",
                     key + b"\xc3\xa9", key + b"\xff", b"<<", b"!!null"])
    line = data.count(b"\n", 0, m.start()) + 1
    return _replace_match(data, m, new + b":"), f"rename key {key!r} (line {line}) -> {new!r}"


def scene_deep_nesting(rng, data):
    matches = list(KEY_VALUE_RE.finditer(data))
    depth = pick(rng, [64, 1000, 10000, 100000])
    kind = rng.randrange(3)
    if kind == 0:
        nest = b"[" * depth + b"1" + b"]" * depth
    elif kind == 1:
        nest = b"{a: " * depth + b"1" + b"}" * depth
    else:
        nest = b"[" * depth  # unbalanced
    if not matches:
        return data + b"\nx: " + nest + b"\n", f"deep nesting depth {depth} appended"
    m = pick(rng, matches)
    line = data.count(b"\n", 0, m.start()) + 1
    out = data[:m.start("val")] + nest + data[m.end("val"):]
    return out, f"value of {m.group('key').decode()!r} (line {line}) -> nesting depth {depth} kind {kind}"


def scene_yaml_feature(rng, data):
    """YAML constructs a strict reader must refuse or handle: aliases, merge keys, documents, tags."""
    choice = rng.randrange(7)
    if choice == 0:  # exponential alias expansion ("billion laughs"), bounded to 10^9 leaves
        lines = [b"a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]"]
        for i in range(1, 10):
            ref = b", ".join([b"*a%d" % (i - 1)] * 10)
            lines.append(b"a%d: &a%d [%s]" % (i, i, ref))
        return b"\n".join(lines) + b"\n" + data, "alias expansion (billion laughs) prepended"
    if choice == 1:
        return data + b"\n---\n" + data, "second YAML document appended"
    if choice == 2:
        return b"%YAML 9.9\n---\n" + data, "YAML directive with unknown version"
    if choice == 3:
        return data.replace(b"materials:", b"materials: &m", 1) + b"\nextra: *m\n", "anchor and alias"
    if choice == 4:
        return b"\xef\xbb\xbf" + data.replace(b"\n", b"\r\n"), "UTF-8 BOM and CRLF line ends (valid)"
    if choice == 5:
        return data.replace(b"  ", b"\t", 1), "tab in indentation"
    n = pick(rng, [10**5, 10**6])
    return data.replace(b"title:", b"title: " + b"x" * n + b" #", 1), f"title of {n} characters"


def scene_number(rng, data):
    return replace_number(rng, data)


def scene_set_override(rng, data):
    """Returns the data unchanged and a list of --set arguments (the driver passes them to fsi run)."""
    tree = yaml.safe_load(data)
    paths = [p for p, _ in _yaml_paths(tree)] or [("title",)]
    kind = rng.randrange(4)
    if kind == 0:
        path = _path_text(pick(rng, paths))
        arg = f"{path}={pick(rng, SPECIAL_NUMBERS)}"
    elif kind == 1:
        path = _path_text(pick(rng, paths))
        arg = f"{path}={pick(rng, WRONG_TYPES)}"
    elif kind == 2:
        path = _path_text(pick(rng, paths))
        segs = path.split(".")
        segs[rng.randrange(len(segs))] = pick(rng, ["", "99999999999999999999", "-1", "2147483648", "x",
                                                    "0", " ", "\udcff", "é"])
        arg = ".".join(segs) + "=" + pick(rng, ["1", "{}", "[", "x: y"])
    else:
        arg = pick(rng, ["", "=", "=1", "noequals", "a..b=1", ".=1", "title=", "title=[", "title={",
                         "time={end: 0}", "meshes=[]", "materials=~", "constraints.0=", "effects=1",
                         "x" * 100000 + "=1", "title=\udcff", "constraints.-0.fix=z", "a.b.c.d.e.f.g=1"])
    shown = arg if len(arg) <= 120 else f"{arg[:60]}...({len(arg)} characters)...{arg[-20:]}"
    return data, f"--set {shown!r}", [arg]


SCENE_MUTATIONS = [
    (scene_number, 6), (scene_wrong_type, 4), (scene_delete_key, 4), (scene_swap_values, 2),
    (scene_duplicate_key, 3), (scene_rename_key, 2), (scene_deep_nesting, 1), (scene_yaml_feature, 2),
    (scene_set_override, 4), (truncate, 2), (insert_bytes, 2), (non_utf8, 2), (delete_line, 2),
    (duplicate_line, 1), (swap_lines, 1), (byte_flip, 1), (delete_bytes, 1),
]


def weighted(rng, table):
    total = sum(w for _, w in table)
    r = rng.uniform(0, total)
    for f, w in table:
        r -= w
        if r <= 0:
            return f
    return table[-1][0]


def mutate_scene(rng, data):
    """1-3 stacked mutations. Returns (bytes, [descriptions], [--set args])."""
    descs, sets = [], []
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        f = weighted(rng, SCENE_MUTATIONS)
        try:
            r = f(rng, data)
        except (yaml.YAMLError, TypeError, KeyError, IndexError, AttributeError, RecursionError):
            # A structural mutation needs parseable YAML; after a byte-level one it may not be: fall back.
            r = insert_bytes(rng, data)
        if len(r) == 3:
            data, d, s = r
            sets += s
        else:
            data, d = r
        descs.append(d)
    return data, descs, sets


# ---------------------------------------------------------------------------------------------------------
# Gmsh files

SECTION_RE = re.compile(rb"^\$(\w+)\r?$", re.M)


def _is_binary(data):
    """True for a binary MSH file (MeshFormat file-type 1): its bodies are not text."""
    m = re.match(rb"\$MeshFormat\r?\n\S+ (\d)", data)
    return m and m.group(1) == b"1"


def gmsh_section_header(rng, data):
    matches = list(SECTION_RE.finditer(data))
    if not matches:
        return insert_bytes(rng, data)
    m = pick(rng, matches)
    name = m.group(1)
    kind = rng.randrange(5)
    if kind == 0:
        flipped = name[3:] if name.startswith(b"End") else b"End" + name  # $Nodes <-> $EndNodes
        new = b"$" + pick(rng, [name[:-1], name + b"s", name.lower(), b"End" + name, flipped])
        out = _replace_match(data, m, new)
        desc = f"section header {name.decode()} -> {new.decode()}"
    elif kind == 1:
        out = data[:m.start()] + data[m.end() + 1:]
        desc = f"delete section header ${name.decode()}"
    elif kind == 2:  # duplicate a whole section (ASCII: after itself)
        end = data.find(b"$End" + name, m.end())
        if name.startswith(b"End") or end < 0:
            return gmsh_count(rng, data)
        end = data.find(b"\n", end) + 1
        out = data[:end] + data[m.start():end] + data[end:]
        desc = f"duplicate section ${name.decode()}"
    elif kind == 3:  # drop a whole section
        end = data.find(b"$End" + name, m.end())
        if name.startswith(b"End") or end < 0:
            return gmsh_count(rng, data)
        end = data.find(b"\n", end) + 1
        out = data[:m.start()] + data[end:]
        desc = f"delete section ${name.decode()}"
    else:  # MeshFormat line: version, file type, data size
        fm = re.search(rb"\$MeshFormat\r?\n(\S+) (\S+) (\S+)", data)
        if not fm:
            return gmsh_count(rng, data)
        g = rng.randrange(1, 4)
        new = pick(rng, [b"0", b"1", b"2", b"4", b"16", b"-8", b"2.0", b"3.0", b"4.0", b"4.2", b"5", b"nan",
                         b"99999999999", b"x"])
        out = data[:fm.start(g)] + new + data[fm.end(g):]
        desc = f"MeshFormat field {g} {fm.group(g).decode()} -> {new.decode()}"
    return out, desc


def gmsh_count(rng, data):
    """An integer of the text part (counts, tags, entity numbers, element types) -> edge case."""
    binary = _is_binary(data)
    if binary:
        # Only the lines that are plain text: MeshFormat, PhysicalNames, and 2.2's count lines.
        matches = []
        for m in re.finditer(rb"^[-\d ]+\r?$", data, re.M):
            if all(32 <= c < 127 or c in (10, 13) for c in m.group()):
                matches.extend(INTEGER_RE.finditer(data, m.start(), m.end()))
    else:
        matches = list(INTEGER_RE.finditer(data))
    return replace_integer(rng, data, matches)


def gmsh_number(rng, data):
    if _is_binary(data):
        return gmsh_binary_word(rng, data)
    return replace_number(rng, data)


def _binary_bodies(data):
    """Byte ranges of the binary bodies: from the line after a section header to its $End line."""
    out = []
    for name in (b"Entities", b"Nodes", b"Elements", b"PartitionedEntities", b"Periodic"):
        start = data.find(b"$" + name + b"\n")
        end = data.find(b"$End" + name, start + 1)
        if start >= 0 and end > start:
            out.append((name.decode(), start + len(name) + 2, end))
    return out


def gmsh_binary_word(rng, data):
    """Overwrites a 4- or 8-byte little-endian word of a binary body with an integer edge case or a
    special double (counts, tags, types, coordinates)."""
    bodies = [b for b in _binary_bodies(data) if b[2] - b[1] >= 8]
    if not bodies:
        return byte_flip(rng, data)
    name, lo, hi = pick(rng, bodies)
    size = pick(rng, [4, 8, 8])
    off = rng.randrange(lo, hi - size + 1)
    # Prefer aligned offsets relative to the body start (most fields are 4- or 8-byte words).
    off = lo + ((off - lo) // 4) * 4
    if rng.random() < 0.25:
        val = pick(rng, [float("nan"), float("inf"), -float("inf"), 1e308, 5e-324, -0.0])
        word = struct.pack("<d", val)
        size = 8
        desc_val = repr(val)
    else:
        v = special_integer(rng)
        word = (v % (1 << (8 * size))).to_bytes(size, "little")
        desc_val = str(v)
    if off + size > len(data):
        return byte_flip(rng, data)
    out = data[:off] + word + data[off + size:]
    return out, f"binary ${name} offset {off} ({off - lo} into the body): {size}-byte word -> {desc_val}"


def gmsh_element_line(rng, data):
    """ASCII: changes the structure of one element line (type, number of tags, node count)."""
    if _is_binary(data):
        return gmsh_binary_word(rng, data)
    start = data.find(b"$Elements\n")
    end = data.find(b"$EndElements", start + 1)
    if start < 0 or end < 0:
        return gmsh_count(rng, data)
    body = data[start:end]
    lines = [m for m in re.finditer(rb"^[^\n$]*$", body, re.M) if len(m.group().split()) >= 2]
    if not lines:
        return gmsh_count(rng, data)
    m = pick(rng, lines)
    tokens = m.group().split()
    kind = rng.randrange(3)
    if kind == 0 and len(tokens) > 1:
        i = rng.randrange(len(tokens))
        old = int(tokens[i]) if tokens[i].lstrip(b"-").isdigit() else None
        tokens[i] = str(special_integer(rng, old)).encode()
        desc = f"element line token {i}"
    elif kind == 1:
        del tokens[rng.randrange(len(tokens))]
        desc = "element line: one token removed"
    else:
        tokens.insert(rng.randrange(len(tokens) + 1), str(special_integer(rng)).encode())
        desc = "element line: one token inserted"
    new = b" ".join(tokens)
    line = data.count(b"\n", 0, start + m.start()) + 1
    out = data[:start + m.start()] + new + data[start + m.end():]
    return out, f"{desc} (line {line}): {m.group().decode()!r} -> {new.decode()!r}"


def gmsh_physical_name(rng, data):
    m = re.search(rb'"([^"\n]*)"', data)
    if not m:
        return gmsh_count(rng, data)
    new = pick(rng, [b"", b"x" * 5000, b"sheet\xff", b'a"b', b"\x00", b"sheet", b"rim", b"\xc3"])
    quote = rng.random() < 0.8
    rep = (b'"' + new + b'"') if quote else new
    return _replace_match(data, m, rep), f"physical name {m.group().decode()} -> {rep!r}"


GMSH_MUTATIONS = [
    (gmsh_count, 8), (gmsh_binary_word, 4), (gmsh_element_line, 3), (gmsh_section_header, 3),
    (gmsh_number, 2), (gmsh_physical_name, 1), (byte_flip, 3), (insert_bytes, 2), (delete_bytes, 2),
    (truncate, 2), (delete_line, 2), (duplicate_line, 1), (swap_lines, 1),
]


def mutate_gmsh(rng, data):
    descs = []
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        data, d = weighted(rng, GMSH_MUTATIONS)(rng, data)
        descs.append(d)
    return data, descs


# ---------------------------------------------------------------------------------------------------------
# OpenFOAM polyMesh files

POLYMESH_FILES = ["points", "faces", "owner", "neighbour", "boundary"]
HEADER_END = b"// * * * *"


def _body_start(data):
    i = data.find(HEADER_END)
    return 0 if i < 0 else data.find(b"\n", i) + 1


def foam_list_count(rng, data):
    """The count in front of a list: `42\\n(` or `4(1 2 3 4)`."""
    lo = _body_start(data)
    matches = [m for m in re.finditer(rb"(?<![\w.\-])\d+(?=\s*\()", data) if m.start() >= lo]
    return replace_integer(rng, data, matches)


def foam_label(rng, data):
    lo = _body_start(data)
    matches = [m for m in INTEGER_RE.finditer(data) if m.start() >= lo]
    return replace_integer(rng, data, matches)


def foam_number(rng, data):
    lo = _body_start(data)
    matches = [m for m in NUMBER_RE.finditer(data) if m.start() >= lo]
    if not matches:
        return replace_number(rng, data)
    m = pick(rng, matches)
    new = pick(rng, SPECIAL_NUMBERS + ["abc", "1.0.0", "1e", ";"]).encode()
    line = data.count(b"\n", 0, m.start()) + 1
    return _replace_match(data, m, new), f"number {m.group().decode()!r} -> {new.decode()!r} (line {line})"


def foam_paren(rng, data):
    lo = _body_start(data)
    idx = [i for i in range(lo, len(data)) if data[i:i + 1] in (b"(", b")", b"{", b"}", b";")]
    if not idx:
        return insert_bytes(rng, data)
    i = pick(rng, idx)
    line = data.count(b"\n", 0, i) + 1
    kind = rng.randrange(3)
    if kind == 0:
        return data[:i] + data[i + 1:], f"delete {data[i:i + 1].decode()!r} (line {line})"
    if kind == 1:
        c = pick(rng, [b"(", b")", b"{", b"}", b";"])
        return data[:i] + c + data[i:], f"insert {c.decode()!r} before offset {i} (line {line})"
    c = pick(rng, [b"(", b")", b"{", b"}", b";", b" "])
    return data[:i] + c + data[i + 1:], f"replace {data[i:i + 1].decode()!r} by {c.decode()!r} (line {line})"


def foam_boundary_entry(rng, data):
    """boundary: startFace / nFaces values, a duplicated or renamed patch, a removed key."""
    keys = list(re.finditer(rb"(startFace|nFaces)\s+(\d+)\s*;", data))
    kind = rng.randrange(4)
    if keys and kind <= 1:
        m = pick(rng, keys)
        old = int(m.group(2))
        new = str(special_integer(rng, old)).encode()
        line = data.count(b"\n", 0, m.start()) + 1
        out = data[:m.start(2)] + new + data[m.end(2):]
        return out, f"{m.group(1).decode()} {old} -> {new.decode()} (line {line})"
    if keys and kind == 2:
        m = pick(rng, keys)
        line = data.count(b"\n", 0, m.start()) + 1
        return data[:m.start()] + data[m.end():], f"remove '{m.group().decode()}' (line {line})"
    names = list(re.finditer(rb"^\s{4}(\w+)\s*\n\s{4}\{", data, re.M))
    if not names:
        return foam_list_count(rng, data)
    m = pick(rng, names)
    new = pick(rng, [b"top", b"bottom", b"sides", b"", b"\xff", b"a b", b"x" * 1000])
    out = data[:m.start(1)] + new + data[m.end(1):]
    return out, f"patch name {m.group(1).decode()} -> {new!r}"


def foam_header(rng, data):
    choice = rng.randrange(4)
    if choice == 0:
        return data.replace(b"format      ascii", b"format      binary", 1), "header: format binary"
    if choice == 1:
        new = pick(rng, [b"faceCompactList", b"vectorField", b"labelList", b"polyBoundaryMesh", b"x"])
        return re.sub(rb"class\s+\w+;", b"class " + new + b";", data, count=1), f"header: class {new.decode()}"
    if choice == 2:
        return data[_body_start(data):], "header removed"
    return data.replace(b"FoamFile", b"FoamFil", 1), "header keyword misspelt"


FOAM_MUTATIONS = [
    (foam_list_count, 6), (foam_label, 6), (foam_number, 3), (foam_paren, 3), (foam_boundary_entry, 4),
    (foam_header, 1), (truncate, 2), (insert_bytes, 2), (delete_bytes, 1), (delete_line, 2),
    (duplicate_line, 1), (byte_flip, 1), (non_utf8, 1),
]


def mutate_foam(rng, files):
    """files: {name: bytes} of one polyMesh. Mutates 1-2 of them in place; returns the descriptions."""
    descs = []
    for _ in range(rng.choice([1, 1, 1, 2])):
        name = pick(rng, POLYMESH_FILES)
        f = weighted(rng, FOAM_MUTATIONS)
        if name != "boundary" and f is foam_boundary_entry:
            name = "boundary"
        files[name], d = f(rng, files[name])
        descs.append(f"{name}: {d}")
    return descs


# ---------------------------------------------------------------------------------------------------------
# The parafoil generator's keys (the fuzz family `parafoil`, issue 35): its seed has one generator entry as
# a flow mapping on one line; each mutation changes, deletes or adds keys of that entry, or overrides one
# with --set. Values: 0, negative, huge, subnormal, nan, wrong types, quoted and tagged numbers, null, bad
# NACA designations; and plausible values that interact (bulge with span_divisions 1, cascade 1, no brakes).

PARAFOIL_GENERATOR_RE = re.compile(rb"^(?P<indent>[ \t]*generator:[ \t]*)(?P<map>\{type: parafoil.*\})[ \t]*$", re.M)

# Every key of the generator (structure/parafoil/ParafoilScene.cpp) with plausible values to add.
PARAFOIL_VALUES = {
    "span": ["3.0", "1.0", "8.0", "0.5"],
    "root_chord": ["1.0", "0.5", "2.0"],
    "tip_chord": ["0.6", "1.0", "1.5"],
    "cells": ["1", "2", "3", "6"],
    "arc_radius": ["0", "3.0", "1.0", "100"],
    "incidence": ["0", "10", "-5"],
    "twist": ["0", "5", "-10"],
    "section": ["NACA 2412", "0012", "naca23012", "NACA 23112", "NACA 0001"],
    "thickness_scale": ["0.5", "2.0", "5"],
    "intake": ["closed", "{from: 0.0, to: 0.1}", "{from: 0.02, to: 0.04}"],
    "chordwise_points": ["4", "6", "20"],
    "span_divisions": ["1", "3"],
    "chordwise_spacing": ["cosine", "half_cosine"],
    "bulge": ["0", "0.1", "0.5"],
    "ribs": ["all", "alternate"],
    "rows": ["[0.2, 0.5]", "[0.5]", "[0.1, 0.2, 0.3, 0.4, 0.5]"],
    "cascade": ["1", "2", "3"],
    "cascade_fraction": ["0.1", "0.9"],
    "line_length": ["0.5", "2.0", "10"],
    "rigging_angle": ["0", "20", "-10"],
    "line_elements": ["1", "3"],
    "row_trim": ["[0, 0, 0, 0]", "[-0.1, 0, 0.1, 0.2]", "[0.1, 0.2]"],
    "brake_points": ["0", "1", "2"],
    "toggle_fraction": ["0", "0.5"],
    "brake_slack": ["0", "0.1"],
    "trailing_edge_tape": ["true", "false"],
    "riser_length": ["0.1", "1.0", "30"],
}
PARAFOIL_SPECIAL = [
    "0", "-1", "-0.5", "1e308", "-1e308", "1e30", "1e400", "1e-320", "4.9e-324", ".nan", ".inf", "-.inf",
    "2147483648", "9223372036854775808", "1e9", "abc", "'1.5'", '"2"', "!!str 3", "!!float 2", "!!int 1.5",
    "!!null", "null", "~", "''", "[]", "[1, 2]", "{a: 1}", "true", "0x10", "1_000", "!foo 1",
    "NACA -4415", "NACA 44-15", "NACA 4 415", "NACA 44155", "NACA 9999", "'NACA 4415'",
]


def _parafoil_entries(text):
    """The generator's entries as [(key, raw value text)], splitting the flow mapping at top-level commas."""
    inner = text.strip()[1:-1]
    entries, depth, start = [], 0, 0
    for i, c in enumerate(inner + ","):
        if c in "[{":
            depth += 1
        elif c in "]}":
            depth -= 1
        elif c == "," and depth == 0:
            part = inner[start:i].strip()
            start = i + 1
            if part:
                k, _, v = part.partition(":")
                entries.append((k.strip(), v.strip()))
    return entries


def mutate_parafoil(rng, data):
    """1-3 mutations of the parafoil generator's keys; returns (bytes, descriptions, --set overrides)."""
    m = PARAFOIL_GENERATOR_RE.search(data)
    entries = _parafoil_entries(m.group("map").decode())
    desc, sets = [], []
    keys = list(PARAFOIL_VALUES)
    for _ in range(1 + int(rng.random() < 0.5) + int(rng.random() < 0.25)):
        present = [k for k, _ in entries if k != "type"]
        r = rng.random()
        if r < 0.45:  # an edge value for a key (present or not)
            key = pick(rng, present if present and rng.random() < 0.8 else keys)
            value = pick(rng, PARAFOIL_SPECIAL)
            entries = [(k, v) for k, v in entries if k != key] + [(key, value)]
            desc.append(f"parafoil: {key}: {value}")
        elif r < 0.6 and present:  # a key deleted: its default (or "unset") applies
            key = pick(rng, present)
            entries = [(k, v) for k, v in entries if k != key]
            desc.append(f"parafoil: {key} deleted")
        elif r < 0.85:  # a plausible value: combinations the generator must accept or refuse clearly
            key = pick(rng, keys)
            value = pick(rng, PARAFOIL_VALUES[key])
            entries = [(k, v) for k, v in entries if k != key] + [(key, value)]
            desc.append(f"parafoil: {key}: {value}")
        elif r < 0.95:  # the same through --set (also the empty value)
            key = pick(rng, keys)
            value = pick(rng, PARAFOIL_SPECIAL + PARAFOIL_VALUES[key] + [""])
            sets.append(f"meshes.wing.generator.{key}={value}")
            desc.append(f"--set meshes.wing.generator.{key}={value}")
        else:  # a key the generator does not have, or the entry's type changed
            if rng.random() < 0.5:
                entries.append(("spn", "3.0"))
                desc.append("parafoil: unknown key spn")
            else:
                entries = [(k, pick(rng, ["parafol", "''", "7", "[parafoil]"]) if k == "type" else v)
                           for k, v in entries]
                desc.append("parafoil: type changed")
    body = "{" + ", ".join(f"{k}: {v} " for k, v in entries) + "}"
    out = data[:m.start("map")] + body.encode() + data[m.end("map"):]
    return out, desc, sets


def parafoil_given(data, sets):
    """{key: raw value text} of the generator entry as fsi sees it: the file's entry, then the --set values."""
    m = PARAFOIL_GENERATOR_RE.search(data)
    given = dict(_parafoil_entries(m.group("map").decode())) if m else {}
    for s in sets:
        path, _, value = s.partition("=")
        if path.startswith("meshes.wing.generator."):
            given[path[len("meshes.wing.generator."):]] = value.strip()
    return given
