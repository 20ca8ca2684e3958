#!/usr/bin/env python3
"""The spectrograms of a recorded strike and of its match side by side, as one PNG.

    python3 Lab/match_spectrograms.py RECORDING MATCH OUT.png [--seconds S] [--titles A B]

RECORDING and MATCH are WAV or FLAC files holding one strike each (channels averaged), e.g. a
recording and a render of the preset snaresim-render --match wrote for it:

    snaresim-render --match Snare-2.wav -o snare2.snarepreset            # prints the velocity
    snaresim-render --preset snare2.snarepreset --hit 0:VELOCITY --seconds 1 --sample-rate 48000 -o match.wav
    python3 Lab/match_spectrograms.py Snare-2.wav match.wav docs/images/match-snare-2.png

Both are shown from their onset (the first sample within 20 dB of the largest, less 1 ms, as
snare_features.py finds it) for S seconds (default 0.6), on a log frequency axis from 40 Hz,
Hann windows of 2048 samples at 48 kHz (scaled with the rate), 75 % overlap, each in dB of its
own largest value over 80 dB: the levels of a recording are arbitrary, the match compares them
normalised. Needs numpy, matplotlib and python3-soundfile.
"""

import argparse
import sys

import numpy as np


def strike(path, seconds):
    import soundfile
    x, rate = soundfile.read(path, dtype='float64', always_2d=True)
    x = x.mean(axis=1)
    x = x - x.mean()
    top = np.abs(x).max()
    onset = max(0, int(np.argmax(np.abs(x) >= 0.1 * top)) - int(round(0.001 * rate)))
    return x[onset:onset + int(round(seconds * rate))], float(rate)


def spectrogram(x, rate):
    n = max(16, int(round(2048 * rate / 48000.0)))
    hop = n // 4
    window = np.hanning(n)
    frames = [x[i:i + n] for i in range(0, max(1, len(x) - n + 1), hop)]
    power = np.array([np.abs(np.fft.rfft(window * np.pad(f, (0, n - len(f))))) ** 2 for f in frames]).T
    db = 10.0 * np.log10(np.maximum(power / power.max(), 1e-12))
    times = (np.arange(len(frames)) * hop + n / 2) / rate
    return times, np.fft.rfftfreq(n, 1.0 / rate), db


def main():
    parser = argparse.ArgumentParser(description='Spectrograms of a recorded strike and its match, side by side.')
    parser.add_argument('recording')
    parser.add_argument('match')
    parser.add_argument('out')
    parser.add_argument('--seconds', type=float, default=0.6)
    parser.add_argument('--titles', nargs=2, default=None, metavar=('A', 'B'))
    args = parser.parse_args()

    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    titles = args.titles or [args.recording.rsplit('/', 1)[-1], args.match.rsplit('/', 1)[-1]]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), sharey=True, constrained_layout=True)
    for ax, path, title in zip(axes, (args.recording, args.match), titles):
        x, rate = strike(path, args.seconds)
        t, f, db = spectrogram(x, rate)
        mesh = ax.pcolormesh(1e3 * t, f, db, vmin=-80.0, vmax=0.0, cmap='magma', shading='auto')
        ax.set_yscale('log')
        ax.set_ylim(40.0, rate / 2.0)
        ax.set_xlabel('time after the onset (ms)')
        ax.set_title(title)
    axes[0].set_ylabel('frequency (Hz)')
    fig.colorbar(mesh, ax=axes, label='dB of the largest value', shrink=0.9)
    fig.savefig(args.out, dpi=100)
    return 0


if __name__ == '__main__':
    sys.exit(main())
