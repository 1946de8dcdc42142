"""Cycles' per-object random number for the Object Info node: a hash of the object's name
(Cycles' hash_string, then Bob Jenkins' lookup3 hash of two words, as shading/hash.h in the
native library), so Random matches between Photon and Cycles."""

_MASK = 0xFFFFFFFF


def _rot(x, k):
    return ((x << k) | (x >> (32 - k))) & _MASK


def _final(a, b, c):
    c ^= b; c = (c - _rot(b, 14)) & _MASK
    a ^= c; a = (a - _rot(c, 11)) & _MASK
    b ^= a; b = (b - _rot(a, 25)) & _MASK
    c ^= b; c = (c - _rot(b, 16)) & _MASK
    a ^= c; a = (a - _rot(c, 4)) & _MASK
    b ^= a; b = (b - _rot(a, 14)) & _MASK
    c ^= b; c = (c - _rot(b, 24)) & _MASK
    return c


def hash_uint2(kx, ky):
    a = b = c = (0xdeadbeef + (2 << 2) + 13) & _MASK
    b = (b + ky) & _MASK
    a = (a + kx) & _MASK
    return _final(a, b, c)


def hash_string(text):
    value = 0
    for byte in text.encode("utf-8"):
        value = (value * 37 + byte) & _MASK
    return value
