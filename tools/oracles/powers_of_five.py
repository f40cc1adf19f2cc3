"""Entries of the Eisel-Lemire table of 128-bit powers of five (crates/thermonav-io/src/
decimal_value.rs), computed with Python's exact integers from Lemire's construction (Number
Parsing at a Gigabyte per Second, 2021): for -27 <= q < 0, floor(2^(z + 127) / 5^-q) + 1 with
2^z the first power of two at least 5^-q; for q >= 0, 5^q doubled until its top bit is bit 127. Prints [high, low] words as the test asserts them."""

for q in [-1, -2, -27, 0, 1, 22]:
    if q < 0:
        p = 5 ** -q
        z = 0
        while (1 << z) < p:
            z += 1
        c = 2 ** (z + 127) // p + 1
    else:
        c = 5 ** q
        while c < 1 << 127:
            c *= 2
    print(q, hex(c >> 64), hex(c & ((1 << 64) - 1)))
