#!/usr/bin/env python3
"""The air box's figures and tables in docs/MODEL.md, from a build (numpy, scipy, matplotlib).

    python3 Lab/airbox_figures.py [--build build] [--images docs/images] PART ...

PART is one or more of (default: all of them):
  band        section 5.3: the struck batter alone in the box, sigma_a = 0 and 2e-6 m; the two
              spectrograms (airbox-band-sigma0.png, airbox-band-sigma2e-6.png) and the band's
              decay rates (airbox_figures band)
  pairs       the batter's (0,1) mode in vacuum and in air, the heads' (0,1) pair in the cavity
              and the box: frequencies and decay rates (airbox_figures pairs)
  s52         section 5.2 in the cavity and the box, and the variations (airbox_figures s52)
  recordings  the default drum in the air box (snaresim-render --model airbox, 1 s at 48 kHz,
              velocities 60, 100, 127, and 100 with the snares off), its close top mic against
              the recorded snare drums of Debian's hydrogen-drumkits: scripts/snare_features.py's
              table, airbox-vs-recordings-spectrum.png and airbox-vs-recordings-envelopes.png

--work DIR keeps the renders there and uses those it finds (delete them after a change of the
model). Needs airbox_figures and snaresim-render built in the build folder (cmake --build build --target
airbox_figures snaresim-render). The air box's parts take minutes (the renders most).
"""

import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'scripts'))
import snare_features  # noqa: E402
from recordings import RECORDINGS  # noqa: E402

RENDERS = [('model v60', 60, True), ('model v100', 100, True), ('model v127', 127, True), ('model v100, snares off', 100, False)]


def plt():
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as pyplot
    return pyplot


def run(args):
    print('$ ' + ' '.join(args), flush=True)
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    print(out, end='', flush=True)
    return out


def spectrogram_png(path, wav, title):
    from scipy.io import wavfile
    from scipy.signal import stft
    rate, x = wavfile.read(wav)
    # as the paper's Fig. 4: Hann window of 512 samples, 75 % overlap
    f, t, Z = stft(x.astype(np.float64), fs=rate, window='hann', nperseg=512, noverlap=384, boundary=None, padded=False)
    db = 20.0 * np.log10(np.abs(Z) + 1e-30)
    db -= db.max()
    pyplot = plt()
    fig, ax = pyplot.subplots(figsize=(8, 4.5), dpi=100)
    mesh = ax.pcolormesh(t, f / 1000.0, db, vmin=-100, vmax=0, cmap='magma', shading='auto')
    for frac in (0.196, 0.304):  # the worst axial and side-diagonal dispersion (section 5.3)
        ax.annotate('%.3f Fs' % frac, xy=(1.0, frac * rate / 1000.0), xycoords=('axes fraction', 'data'),
                    xytext=(-48, 4), textcoords='offset points', color='w', fontsize=8)
    ax.set_xlabel('time (s)')
    ax.set_ylabel('frequency (kHz)')
    ax.set_title(title, fontsize=10)
    fig.colorbar(mesh, ax=ax, label='dB (0 = the loudest frame and bin)')
    fig.tight_layout()
    fig.savefig(path)
    pyplot.close(fig)
    print('wrote ' + path)


def band(build, images):
    with tempfile.TemporaryDirectory() as tmp:
        run([os.path.join(build, 'Lab/airbox_figures'), 'band', tmp, '1.0', '0.6'])
        for name, sigma in (('sigma0', '0'), ('sigma2e-6', '2e-6 m')):
            spectrogram_png(os.path.join(images, 'airbox-band-%s.png' % name), os.path.join(tmp, 'band-%s.wav' % name),
                            'Batter alone in the 0.6 m air box, struck; pressure 0.1 m above it on a diagonal; '
                            'sigma_a = %s\n(Hann 512, 75 %% overlap, 44.1 kHz)' % sigma)


def third_octave_spectrum(x, rate, onset, seconds=0.5):
    """Power spectrum of the first `seconds` after the onset in 1/6-octave bands from 40 Hz,
    as a share of the segment's energy per band (dB), and the bands' centres."""
    seg = x[onset:onset + int(seconds * rate)]
    seg = seg * np.hanning(2 * len(seg))[len(seg):]  # a half-Hann fade to the segment's end
    p = np.abs(np.fft.rfft(seg)) ** 2
    f = np.fft.rfftfreq(len(seg), 1.0 / rate)
    edges = 40.0 * 2.0 ** (np.arange(0, 6 * np.log2(20000.0 / 40.0) + 1) / 6.0)
    centres = np.sqrt(edges[:-1] * edges[1:])
    power = np.array([p[(f >= lo) & (f < hi)].sum() for lo, hi in zip(edges[:-1], edges[1:])])
    return centres, 10.0 * np.log10(power / p.sum() + 1e-30)


def recordings(build, images, work=None):
    render = os.path.join(build, 'Source/Renderer/snaresim-render')
    missing = [name for name, files in RECORDINGS if not files]
    if missing:
        sys.exit('airbox_figures.py: no recordings for %s: apt-get install hydrogen-drumkits' % ', '.join(missing))
    groups = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, velocity, snares in RENDERS:
            wav = os.path.join(work or tmp, 'airbox-v%d%s.wav' % (velocity, '' if snares else '-off'))
            if os.path.exists(wav):
                print('using ' + wav)
                groups.append((name, [wav], 0))
                continue
            args = [render, '-o', wav, '--hit', '0:%d' % velocity, '--seconds', '1', '--sample-rate', '48000', '--model', 'airbox']
            if not snares:
                args += ['--set', 'snares_engaged=off']
            run(args)
            groups.append((name, [wav], 0))  # channel 0: the close top mic
        groups += [(name, files, None) for name, files in RECORDINGS]

        # The features: each file's, then each group's mean and range.
        print('\n| | ' + ' | '.join(name for name, _, _ in groups) + ' |')
        print('|---' * (len(groups) + 1) + '|')
        results = [[snare_features.features(f, channel) for f in files] for _, files, channel in groups]
        rows = [('tail centroid 50-300 ms (Hz)', lambda r: r['tail_centroid_hz'], '%.0f')]
        rows += [('share %s Hz, 0-300 ms (%%)' % b, (lambda b: lambda r: 100.0 * r['band_shares'][b])(b), '%.1f')
                 for b in snare_features.BAND_NAMES]
        rows += [('fall 20 dB (ms)', lambda r: r['fall_20db_ms'], '%.0f'),
                 ('fall 40 dB (ms)', lambda r: r['fall_40db_ms'], '%.0f'),
                 ('lowest strong peak (Hz)', lambda r: r['lowest_peak_hz'], '%.0f')]
        for label, get, fmt in rows:
            cells = []
            for group in results:
                values = [get(r) for r in group]
                if any(v is None for v in values):
                    cells.append('n/a' if all(v is None for v in values) else 'some n/a')
                elif len(values) == 1:
                    cells.append(fmt % values[0])
                else:
                    cells.append((fmt + ' (' + fmt + '-' + fmt + ')') % (np.mean(values), min(values), max(values)))
            print('| %s | %s |' % (label, ' | '.join(cells)))

        # The spectra and the envelopes.
        pyplot = plt()
        fig, ax = pyplot.subplots(figsize=(8, 4.5), dpi=100)
        fig2, ax2 = pyplot.subplots(figsize=(8, 4.5), dpi=100)
        styles = {'model': dict(lw=1.8), 'rec': dict(lw=1.0, ls='--')}
        for (name, files, channel), colour in zip(groups, pyplot.rcParams['axes.prop_cycle'].by_key()['color'] * 2):
            spectra, envelopes = [], []
            for path in files:
                x, rate, onset = snare_features.load_strike(path, channel)
                centres, s = third_octave_spectrum(x, rate, onset)
                spectra.append(s)
                env = snare_features.envelope_db(x, rate)
                t = (np.arange(len(x)) - onset) / rate
                keep = (t >= 0.0) & (t <= 0.8)
                envelopes.append(np.interp(np.arange(0.0, 0.8, 0.001), t[keep], env[keep]))
            style = styles['model' if name.startswith('model') else 'rec']
            ax.semilogx(centres, 10.0 * np.log10(np.mean(10.0 ** (np.array(spectra) / 10.0), axis=0)), color=colour, label=name, **style)
            ax2.plot(1e3 * np.arange(0.0, 0.8, 0.001), np.mean(envelopes, axis=0), color=colour, label=name, **style)
        ax.set_xlim(40, 20000)
        ax.set_ylim(-60, 0)
        ax.set_xlabel('frequency (Hz)')
        ax.set_ylabel('share of the energy per 1/6 octave (dB)')
        ax.set_title('First 500 ms after the onset: the air box\'s close top mic (solid) and recorded snare drums\n'
                     '(dashed; hydrogen-drumkits, the mean of each set\'s files)', fontsize=10)
        ax.grid(True, which='both', alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(images, 'airbox-vs-recordings-spectrum.png'))
        ax2.set_xlim(0, 800)
        ax2.set_ylim(-70, 2)
        ax2.set_xlabel('time after the onset (ms)')
        ax2.set_ylabel('level, RMS over 10 ms (dB of its largest value)')
        ax2.set_title('Decay: the air box\'s close top mic (solid) and recorded snare drums (dashed, the mean of each set in dB)',
                      fontsize=10)
        ax2.grid(True, alpha=0.3)
        ax2.legend(fontsize=8)
        fig2.tight_layout()
        fig2.savefig(os.path.join(images, 'airbox-vs-recordings-envelopes.png'))
        print('wrote ' + os.path.join(images, 'airbox-vs-recordings-spectrum.png'))
        print('wrote ' + os.path.join(images, 'airbox-vs-recordings-envelopes.png'))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('parts', nargs='*', metavar='PART', help='band, pairs, s52, recordings (default: all)')
    parser.add_argument('--build', default='build')
    parser.add_argument('--images', default='docs/images')
    parser.add_argument('--work', default=None, help='keep the renders in this folder and use those found there')
    args = parser.parse_args()
    known = ['band', 'pairs', 's52', 'recordings']
    parts = args.parts or known
    for part in parts:
        if part not in known:
            parser.error('unknown part %s (choose from %s)' % (part, ', '.join(known)))
    figures = os.path.join(args.build, 'Lab/airbox_figures')
    for part in parts:
        if part == 'band':
            band(args.build, args.images)
        elif part == 'pairs':
            run([figures, 'pairs'])
        elif part == 's52':
            run([figures, 's52'])
        elif part == 'recordings':
            recordings(args.build, args.images, args.work)
    return 0


if __name__ == '__main__':
    sys.exit(main())
