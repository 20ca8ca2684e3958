#!/usr/bin/env python3
"""Regenerate docs/RESULTS.md from a build: speed, energy drift and the presets' distances.

    /usr/bin/python3 scripts/results.py --build build [--out docs/RESULTS.md] [--quick]

Runs the build's renderer (BUILD/Source/Renderer/snaresim-render) and scripts/preset_table.py
from the repository root and writes one Markdown page naming the commit, the date, the machine
and the exact command of every figure:

  - speed: snaresim-render --bench --json --bench-repeat 3 for the default scenario at 48 kHz,
    the roll (--bench-scenario roll), 96 kHz (--sample-rate 96000), Quality 1 (--set
    bandwidth=21100, the finest grids), and the default with SNARESIM_VECTOR_TARGET=avx2 and
    =baseline; from each JSON report realtime_factor, compute_seconds_per_audio_second,
    worst_block_ms and worst_block_share, and the default run's step profile;
  - energy: energy_relative_drift_max of a lossless fortissimo strike (0.5 s), with the batter
    in single precision (the default) and in double (--set head_precision=double);
  - presets: preset_table.py --build BUILD --json: each factory preset's nearest recording and
    its distance in dB at velocities 60, 100 and 127 (needs numpy, scipy, python3-soundfile and
    Debian's hydrogen-drumkits; about 30 s).

--quick (to try the script, not for the page): --bench-short (or 0.25 s) and one repeat, and the
preset table for Studio Default only with 0.5 s strikes. Its figures mean nothing; write it
elsewhere (--out /tmp/results-quick.md).

SNARESIM_VECTOR_TARGET in the caller's environment is ignored: each command runs with the
environment the page shows. The page is written to a temporary file beside --out and renamed over it once every command has
succeeded: a failure leaves the old page as it was. A missing build or renderer: a message on
stderr, exit status 2; a command that fails: the command and its stderr on stderr, exit status 1.
"""

import argparse
import datetime
import json
import os
import platform
import re
import shlex
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RENDERER = os.path.join('Source', 'Renderer', 'snaresim-render')
REPEATS = 3
TIMEOUT_S = 3600  # per command

# (label, environment, options after --bench --json): the speed runs.
SPEED_RUNS = [
    ('default scenario, 48 kHz', {}, []),
    ('roll', {}, ['--bench-scenario', 'roll']),
    ('default scenario, 96 kHz', {}, ['--sample-rate', '96000']),
    ('Quality 1 (the finest grids)', {}, ['--set', 'bandwidth=21100']),
    ('default scenario, the avx2 path', {'SNARESIM_VECTOR_TARGET': 'avx2'}, []),
    ('default scenario, the baseline path', {'SNARESIM_VECTOR_TARGET': 'baseline'}, []),
]
SPEED_KEYS = ['realtime_factor', 'compute_seconds_per_audio_second', 'worst_block_ms', 'worst_block_share',
              'block_budget_ms', 'vector_target', 'sample_rate', 'seconds_rendered', 'repeats', 'batter_nodes',
              'carry_nodes', 'snare_points']
# (label, options after -o OUT.wav): the lossless strikes.
ENERGY_RUNS = [
    ('the batter in single precision (the default)', []),
    ('the batter in double precision', ['--set', 'head_precision=double']),
]
ENERGY_OPTIONS = ['--hit', '0:127', '--seconds', '0.5', '--lossless', '--json']
PROFILE_ORDER = ['batter_free', 'carry_free', 'wires_free', 'mallets_free', 'mallet_contact', 'snare_contact',
                 'cavity', 'energy', 'signals', 'advance']


class Failed(Exception):
    """A command failed or printed something unusable: the message says which."""


def shown(args, env=None):
    """The command as a shell would take it, environment first."""
    prefix = ['%s=%s' % (k, shlex.quote(v)) for k, v in sorted((env or {}).items())]
    return ' '.join(prefix + [shlex.quote(a) for a in args])


def run(args, env=None, cwd=REPO):
    """Run a command from the repository root; its stdout, or Failed with its stderr."""
    full_env = dict(os.environ)
    # The vector path is the processor's widest unless the command itself forces one.
    full_env.pop('SNARESIM_VECTOR_TARGET', None)
    full_env.update(env or {})
    try:
        done = subprocess.run(args, cwd=cwd, env=full_env, capture_output=True, text=True, timeout=TIMEOUT_S)
    except FileNotFoundError as e:
        raise Failed('cannot run %s: %s' % (shown(args, env), e))
    except subprocess.TimeoutExpired:
        raise Failed('timed out after %d s: %s' % (TIMEOUT_S, shown(args, env)))
    if done.returncode != 0:
        raise Failed('command failed (exit status %d): %s\n%s'
                     % (done.returncode, shown(args, env), done.stderr.rstrip() or '(nothing on stderr)'))
    return done.stdout


def run_json(args, env=None, keys=()):
    out = run(args, env)
    try:
        report = json.loads(out)
    except ValueError:
        raise Failed('not one JSON object on stdout: %s\n%s' % (shown(args, env), out[:2000]))
    missing = [k for k in keys if k not in report]
    if missing:
        raise Failed('the JSON report lacks %s: %s' % (', '.join(missing), shown(args, env)))
    return report


def git(*args):
    return run(['git'] + list(args)).strip()


def commit():
    """The short commit and whether tracked files differ from it."""
    head = git('rev-parse', '--short', 'HEAD')
    dirty = git('status', '--porcelain', '--untracked-files=no') != ''
    return head, dirty


def cpu():
    """(model name, logical cores) from /proc/cpuinfo, else lscpu."""
    model, cores = None, 0
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                key, _, value = line.partition(':')
                key = key.strip()
                if key == 'model name' and model is None:
                    model = value.strip()
                elif key == 'processor':
                    cores += 1
    except OSError:
        pass
    if model is None or cores == 0:
        try:
            info = run(['lscpu'])
            fields = dict((k.strip(), v.strip()) for k, _, v in (l.partition(':') for l in info.splitlines()))
            model = model or fields.get('Model name')
            cores = cores or int(fields.get('CPU(s)', '0') or 0)
        except (Failed, ValueError):
            pass
    return model or 'unknown', cores or os.cpu_count() or 0


def cpu_flags():
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                if line.startswith('flags'):
                    flags = set(line.partition(':')[2].split())
                    return [name for flag, name in (('avx2', 'AVX2'), ('fma', 'FMA'), ('avx512f', 'AVX-512'))
                            if flag in flags]
    except OSError:
        pass
    return []


def os_name():
    try:
        with open('/etc/os-release') as f:
            for line in f:
                if line.startswith('PRETTY_NAME='):
                    return line.partition('=')[2].strip().strip('"')
    except OSError:
        pass
    return platform.system()


def cmake_cache(build):
    """CMAKE_CXX_COMPILER and CMAKE_BUILD_TYPE from BUILD/CMakeCache.txt."""
    values = {}
    with open(os.path.join(build, 'CMakeCache.txt')) as f:
        for line in f:
            m = re.match(r'(CMAKE_CXX_COMPILER|CMAKE_BUILD_TYPE):[A-Z]+=(.*)$', line.rstrip('\n'))
            if m:
                values[m.group(1)] = m.group(2)
    return values


def compiler_version(path):
    try:
        return run([path, '--version']).splitlines()[0].strip()
    except (Failed, IndexError):
        return None


def stale_sources(renderer):
    """Tracked source files modified after the renderer was built (the build may not be of this tree)."""
    built = os.path.getmtime(renderer)
    files = git('ls-files', '--', 'Source', 'CMakeLists.txt').splitlines()
    return [f for f in files if os.path.isfile(os.path.join(REPO, f)) and os.path.getmtime(os.path.join(REPO, f)) > built]


def bench_options(extra, quick):
    if not quick:
        return ['--bench-repeat', str(REPEATS)]
    # --bench-short is the default scenario only; a run with its own scenario is shortened by hand.
    if '--bench-scenario' in extra:
        return ['--seconds', '0.25', '--bench-repeat', '1']
    return ['--bench-short', '--bench-repeat', '1']


def speed(renderer, quick):
    rows = []
    for label, env, extra in SPEED_RUNS:
        args = [renderer, '--bench', '--json'] + bench_options(extra, quick) + extra
        print('results.py: %s' % shown(args, env), file=sys.stderr)
        report = run_json(args, env, SPEED_KEYS + ['profile'])
        rows.append({'label': label, 'command': shown(args, env), 'report': report})
    return rows


def energy(renderer, tmp):
    rows = []
    for label, extra in ENERGY_RUNS:
        wav = os.path.join(tmp, 'energy.wav')
        args = [renderer, '-o', wav] + ENERGY_OPTIONS + extra
        print('results.py: %s' % shown(args), file=sys.stderr)
        report = run_json(args, None, ['energy_relative_drift_max', 'vector_target'])
        os.remove(wav)
        command = shown([renderer, '-o', 'OUT.wav'] + ENERGY_OPTIONS + extra)
        rows.append({'label': label, 'command': command, 'report': report})
    return rows


def presets(build, quick):
    args = [sys.executable, os.path.join('scripts', 'preset_table.py'), '--build', build, '--json']
    if quick:
        args += ['--presets', 'Studio Default', '--seconds', '0.5']
    print('results.py: %s' % shown(args), file=sys.stderr)
    # No __pycache__ left in scripts/ by the modules preset_table.py imports.
    report = run_json(args, {'PYTHONDONTWRITEBYTECODE': '1'}, ['rows', 'velocities', 'seconds'])
    return {'command': shown(args), 'report': report}


def fmt(value, spec):
    return 'n/a' if value is None else spec % value


def page(info, speed_rows, energy_rows, preset_table, quick):
    out = []
    w = out.append
    state = '`%s`%s' % (info['commit'], ' + uncommitted changes' if info['dirty'] else '')
    w('# Results')
    w('')
    w('The figures of one build of SnareSim: how fast the renderer plays the drum, how well the lossless '
      'drum keeps its energy, and how near each factory preset lies to recorded snare drums. This page is '
      'generated by `scripts/results.py` and must not be edited by hand; run `%s` again to regenerate it. '
      'Made at commit %s on %s (%d cores), %s.'
      % (info['regenerate'], state, info['cpu'], info['cores'], info['date']))
    if quick:
        w('')
        w('**A --quick run** (short renders, one repeat, one preset): the figures only show that the script '
          'works; they are not measurements.')
    w('')
    w('How the benchmark measures and what each model and option costs: [BENCHMARKS.md](../BENCHMARKS.md). '
      'Commands run from the repository root.')
    w('')
    w('## Machine and build')
    w('')
    w('| | |')
    w('|---|---|')
    w('| Commit | %s |' % state)
    w('| Date | %s |' % info['date'])
    w('| CPU | %s%s |' % (info['cpu'], ' (%s)' % ', '.join(info['flags']) if info['flags'] else ''))
    w('| Cores | %d (the benchmark uses one) |' % info['cores'])
    w('| Kernel | %s |' % info['kernel'])
    w('| OS | %s |' % info['os'])
    w('| Compiler | `%s`%s |' % (info['compiler'], ', %s' % info['compiler_version'] if info['compiler_version'] else ''))
    w('| Build type | %s |' % (info['build_type'] or '(not set)'))
    w('| Renderer | `%s`, built %s |' % (info['renderer'], info['renderer_built']))
    w('| Load average at the start | %s |' % info['load'])
    if info['stale']:
        w('')
        w('Warning: %d tracked source file(s) modified after the renderer was built (%s%s): the build '
          'may not be of this commit.' % (len(info['stale']), ', '.join('`%s`' % f for f in info['stale'][:5]),
                                          ', ...' if len(info['stale']) > 5 else ''))

    w('')
    w('## Speed')
    w('')
    w('`snaresim-render --bench` plays the drum as the plug-in does, in blocks of 64 samples on one core, '
      'and times each block by its fastest of the repeats. Real-time factor: seconds of audio per second of '
      'compute (above 1: faster than real time); compute: its inverse, seconds of compute per second of '
      'audio; worst block: the slowest 64-sample block and its share of the block\'s duration (above 1: '
      'that block would drop out). The default scenario strikes at velocity 127 every 0.5 s for 2 s; the '
      'roll is 16 strikes 60 ms apart, 1.5 s. The drum is the default one unless the command sets '
      'otherwise.')
    w('')
    w('| run | vector target | real-time factor | compute (s per s of audio) | worst block (ms) | worst block / its duration | batter / carry nodes, snare points |')
    w('|---|---|---|---|---|---|---|')
    for row in speed_rows:
        r = row['report']
        w('| %s | %s | %s | %s | %s | %s | %s / %s, %s |'
          % (row['label'], r['vector_target'], fmt(r['realtime_factor'], '%.2fx'),
             fmt(r['compute_seconds_per_audio_second'], '%.3f'), fmt(r['worst_block_ms'], '%.3f'),
             fmt(r['worst_block_share'], '%.2f'), r['batter_nodes'], r['carry_nodes'], r['snare_points']))
    w('')
    w('Commands (each report is one JSON object; %s):' % ('one run each' if quick else '%d repeats each' % REPEATS))
    w('')
    w('```sh')
    for row in speed_rows:
        w(row['command'])
    w('```')

    default = speed_rows[0]
    profile = default['report']['profile']
    phases = profile.get('phases', {})
    w('')
    w('## Where the time goes')
    w('')
    w('The step profile of the first run above (`%s`), the `profile` member of its report: each phase of '
      '`Drum::step`, in seconds of compute per second of audio and as a share of the phases\' sum. The '
      'profiled run is played once more after the timed ones and counts in no figure above.'
      % default['command'])
    w('')
    w('| phase | s per s of audio | share |')
    w('|---|---|---|')
    for name in PROFILE_ORDER + sorted(k for k in phases if k not in PROFILE_ORDER):
        if name in phases:
            p = phases[name]
            w('| `%s` | %s | %s |' % (name, fmt(p.get('compute_seconds_per_audio_second'), '%.4f'),
                                      fmt(None if p.get('share') is None else 100.0 * p['share'], '%.1f %%')))
    w('| the phases\' sum | %s | |' % fmt(profile.get('compute_seconds_per_audio_second'), '%.4f'))
    w('| the profiled run\'s blocks (the player included) | %s | |'
      % fmt(profile.get('run_compute_seconds_per_audio_second'), '%.4f'))
    w('| the profile\'s overhead against the fastest timed run | %s | |'
      % fmt(None if profile.get('overhead') is None else 100.0 * profile['overhead'], '%+.1f %%'))

    w('')
    w('## Energy')
    w('')
    w('A lossless fortissimo strike (every loss off), 0.5 s at 48 kHz: the largest relative change of the '
      'energy balance (the stored energy + the losses - the energy the strikes gave) over the render, '
      '`energy_relative_drift_max`. A batter in single precision holds it to float round-off, one in double '
      'to double round-off (docs/MODEL.md, "Heads in single precision").')
    w('')
    w('| run | vector target | energy_relative_drift_max |')
    w('|---|---|---|')
    for row in energy_rows:
        w('| %s | %s | %.2e |' % (row['label'], row['report']['vector_target'], row['report']['energy_relative_drift_max']))
    w('')
    w('Commands (`OUT.wav` a temporary file):')
    w('')
    w('```sh')
    for row in energy_rows:
        w(row['command'])
    w('```')

    report = preset_table['report']
    velocities = report['velocities']
    limit = report.get('distance_limit_db')
    w('')
    w('## Factory presets against recorded snare drums')
    w('')
    w('Each factory preset struck once at velocities %s (%g s at 48 kHz, `--mic mix`), its whole-strike '
      'distance (docs/MATCHING.md) to its nearest recording: the snares-on recordings of the dev kits for a '
      'snares-on preset, Forzee\'s snares-off strokes for a snares-off one (docs/MODEL.md, "Factory presets '
      'against recorded snare drums"). The goal is at most %s dB.'
      % (', '.join(str(v) for v in velocities), report['seconds'], fmt(limit, '%g')))
    w('')
    w('| preset | snares | nearest recording | %s |' % ' | '.join('dB at %d' % v for v in velocities))
    w('|---|---|---|%s' % ('---|' * len(velocities)))
    by_preset = {}
    for row in report['rows']:
        by_preset.setdefault(row['preset'], []).append(row)
    for name, rows in by_preset.items():
        nearest = []
        for row in rows:
            if row.get('nearest') and row['nearest'] not in nearest:
                nearest.append(row['nearest'])
        cells = []
        for v in velocities:
            row = next((r for r in rows if r['velocity'] == v), None)
            if row is None or row.get('distance_db') is None:
                cells.append('n/a')
            else:
                cells.append('%.2f%s' % (row['distance_db'], '' if row.get('distance_ok', True) else ' **over**'))
        w('| %s | %s | %s | %s |' % (name, rows[0]['snares'], ' / '.join(nearest) or 'n/a', ' | '.join(cells)))
    w('')
    w('Command (its JSON holds each strike\'s features and checks as well):')
    w('')
    w('```sh')
    w(preset_table['command'])
    w('```')
    w('')
    return '\n'.join(out)


def write_atomically(path, text):
    directory = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(directory):
        raise Failed('no folder %s for %s' % (directory, path))
    fd, tmp = tempfile.mkstemp(dir=directory, prefix='.%s.' % os.path.basename(path), suffix='.tmp')
    try:
        with os.fdopen(fd, 'w') as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.remove(tmp)
        except OSError:
            pass
        raise


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--build', required=True, help='the CMake build folder (with Source/Renderer/snaresim-render)')
    parser.add_argument('--out', default=None,
                        help='the page to write (default: docs/RESULTS.md in the repository)')
    parser.add_argument('--quick', action='store_true',
                        help='short runs to try the script (figures not meaningful; write them elsewhere)')
    args = parser.parse_args()

    build = os.path.abspath(args.build)
    out = os.path.abspath(args.out) if args.out else os.path.join(REPO, 'docs', 'RESULTS.md')
    if not os.path.isdir(build):
        print('results.py: no build folder %s (cmake -B %s -DCMAKE_BUILD_TYPE=Release)' % (build, args.build),
              file=sys.stderr)
        return 2
    if not os.path.isfile(os.path.join(build, 'CMakeCache.txt')):
        print('results.py: %s is not a CMake build folder (no CMakeCache.txt)' % build, file=sys.stderr)
        return 2
    if not os.path.isdir(os.path.dirname(out)):
        print('results.py: no folder %s for the page' % os.path.dirname(out), file=sys.stderr)
        return 2
    renderer_abs = os.path.join(build, RENDERER)
    if not (os.path.isfile(renderer_abs) and os.access(renderer_abs, os.X_OK)):
        print('results.py: no renderer at %s (cmake --build %s --target snaresim-render)' % (renderer_abs, args.build),
              file=sys.stderr)
        return 2
    # The commands as run from the repository root: the build's path relative to it when inside it.
    rel = os.path.relpath(build, REPO)
    build_shown = build if rel.startswith('..') else rel
    renderer = os.path.join(build_shown, RENDERER)

    try:
        head, dirty = commit()
        cache = cmake_cache(build)
        model, cores = cpu()
        compiler = cache.get('CMAKE_CXX_COMPILER') or 'unknown'
        regenerate = '/usr/bin/python3 scripts/results.py --build %s' % shlex.quote(build_shown)
        if out != os.path.join(REPO, 'docs', 'RESULTS.md'):
            out_rel = os.path.relpath(out, REPO)
            regenerate += ' --out %s' % shlex.quote(out if out_rel.startswith('..') else out_rel)
        if args.quick:
            regenerate += ' --quick'
        info = {
            'commit': head, 'dirty': dirty,
            'date': datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC'),
            'cpu': model, 'cores': cores, 'flags': cpu_flags(),
            'kernel': platform.release(), 'os': os_name(),
            'compiler': compiler, 'compiler_version': compiler_version(compiler) if compiler != 'unknown' else None,
            'build_type': cache.get('CMAKE_BUILD_TYPE'),
            'renderer': renderer,
            'renderer_built': datetime.datetime.fromtimestamp(os.path.getmtime(renderer_abs), datetime.timezone.utc)
            .strftime('%Y-%m-%d %H:%M UTC'),
            'load': ', '.join('%.2f' % x for x in os.getloadavg()),
            'stale': stale_sources(renderer_abs),
            'regenerate': regenerate,
        }
        if info['stale']:
            print('results.py: warning: %d tracked source file(s) newer than %s' % (len(info['stale']), renderer),
                  file=sys.stderr)
        speed_rows = speed(renderer, args.quick)
        with tempfile.TemporaryDirectory(prefix='snaresim-results-') as tmp:
            energy_rows = energy(renderer, tmp)
        preset_rows = presets(build_shown, args.quick)
        write_atomically(out, page(info, speed_rows, energy_rows, preset_rows, args.quick))
    except Failed as e:
        print('results.py: %s' % e, file=sys.stderr)
        print('results.py: %s not written' % out, file=sys.stderr)
        return 1
    except OSError as e:
        print('results.py: %s' % e, file=sys.stderr)
        print('results.py: %s not written' % out, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print('results.py: interrupted; %s not written' % out, file=sys.stderr)
        return 130
    print('results.py: wrote %s' % out, file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
