#!/usr/bin/env python3
"""Share of a mono 32-bit float WAV's energy in a frequency band (python3 only, no numpy).

    band_share.py FILE.wav [LOW_HZ HIGH_HZ]     (default band 2000 5000)

The signal is Hann-windowed; the band's energy is the sum of |X_k|^2 over the DFT bins inside
it (each by the Goertzel recurrence), the total is Parseval's sum over the one-sided spectrum.
"""
import math
import struct
import sys


def read_wav(path):
    data = open(path, 'rb').read()
    if data[:4] != b'RIFF' or data[8:12] != b'WAVE':
        sys.exit('band_share.py: %s is not a WAV file' % path)
    pos, rate, samples = 12, None, None
    while pos + 8 <= len(data):
        cid, size = data[pos:pos + 4], struct.unpack('<I', data[pos + 4:pos + 8])[0]
        body = data[pos + 8:pos + 8 + size]
        if cid == b'fmt ':
            fmt, channels, rate = struct.unpack('<HHI', body[:8])
            bits = struct.unpack('<H', body[14:16])[0]
            if channels != 1 or bits != 32:
                sys.exit('band_share.py: expected mono 32-bit float')
        elif cid == b'data':
            samples = struct.unpack('<%df' % (size // 4), body)
        pos += 8 + size + (size & 1)
    return rate, samples


def main():
    if len(sys.argv) not in (2, 4):
        sys.exit(__doc__)
    low, high = (float(sys.argv[2]), float(sys.argv[3])) if len(sys.argv) == 4 else (2000.0, 5000.0)
    rate, x = read_wav(sys.argv[1])
    n = len(x)
    x = [v * (0.5 - 0.5 * math.cos(2.0 * math.pi * i / (n - 1))) for i, v in enumerate(x)]
    total = 0.5 * n * sum(v * v for v in x)  # one-sided sum of |X_k|^2 (Parseval)
    band = 0.0
    for k in range(max(1, math.ceil(low * n / rate)), min(n // 2, math.floor(high * n / rate)) + 1):
        w = 2.0 * math.cos(2.0 * math.pi * k / n)
        s1 = s2 = 0.0
        for v in x:
            s1, s2 = v + w * s1 - s2, s1
        band += s1 * s1 + s2 * s2 - w * s1 * s2
    print('%.4f' % (band / total))


if __name__ == '__main__':
    main()
