"""The LCM type fingerprint of a struct of primitive members, as lcm-gen computes it.

LCM marshalling begins every message with this 8-byte fingerprint (big-endian): a hash of the members' names,
primitive type names and dimensions, not of the struct's name. lcm-gen's hash works in signed 64-bit
arithmetic (arithmetic right shift), each byte of a string added as a signed char; the fingerprint on the wire
is that hash rotated left by one bit. tests/unit/signal_table_test.cpp checks the result against the
getHash() of lcm-gen's own C++ output for every generated type.
"""

MASK = (1 << 64) - 1


def _signed(v: int) -> int:
    v &= MASK
    return v - (1 << 64) if v >> 63 else v


def _update(v: int, c: int) -> int:
    c = c - 256 if c > 127 else c  # a C char
    return _signed(((v << 8) ^ (v >> 55)) + c)


def _update_string(v: int, s: str) -> int:
    b = s.encode()
    v = _update(v, len(b))
    for ch in b:
        v = _update(v, ch)
    return v


LCM_CONST = 0  # lcm_dimension_mode_t: a fixed-size dimension


def struct_hash(members: list[tuple[str, str, list[int]]]) -> int:
    """members: (name, primitive type, fixed dimensions) in declaration order."""
    v = 0x12345678
    for name, typ, dims in members:
        v = _update_string(v, name)
        v = _update_string(v, typ)
        v = _update(v, len(dims))
        for d in dims:
            v = _update(v, LCM_CONST)
            v = _update_string(v, str(d))
    return v


def fingerprint(members: list[tuple[str, str, list[int]]]) -> int:
    """The unsigned 64-bit fingerprint that starts every encoded message of the struct."""
    h = struct_hash(members) & MASK
    return ((h << 1) & MASK) | (h >> 63)
