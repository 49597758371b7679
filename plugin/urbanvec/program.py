"""Finding the `urbanvec` program and reading its machine-readable usage.

The program is the first of these that is an executable answering `--json-usage`: the Processing
setting, <prefix>/bin/urbanvec when `cmake --install` put this plugin under <prefix>, then PATH.

The provider builds its algorithms from `urbanvec --json-usage`, so parameter names, defaults,
bounds and help always match the installed program. The document is cached on disk per program
path, modification time and size, which keeps QGIS start-up from running the program each time.
"""

import json
import os
import shutil
import subprocess

from qgis.core import QgsApplication, QgsSettings

#: Processing setting (Settings > Options > Processing > Providers > urbanvec) holding the program path.
PROGRAM_SETTING = 'URBANVEC_PROGRAM'
_SETTINGS_KEY = '/Processing/Configuration/' + PROGRAM_SETTING
#: Bumped when the cache layout changes.
_CACHE_FORMAT = 1
#: Seconds allowed for `urbanvec --json-usage`.
_USAGE_TIMEOUT = 30


class ProgramNotFound(Exception):
    pass


#: Where users set the program, as the Processing options dialog shows it.
SETTING_PLACE = 'Settings > Options > Processing > Providers > urbanvec > urbanvec program'
#: Where `cmake --install` puts this plugin under its prefix (CMakeLists.txt: URBANVEC_QGIS_PLUGIN_DIR,
#: default ${CMAKE_INSTALL_DATADIR}/qgis/python/plugins); the program goes to <prefix>/bin.
INSTALLED_PLUGIN_DIR = ('share', 'qgis', 'python', 'plugins', 'urbanvec')


def plugin_folder():
    return os.path.dirname(os.path.abspath(__file__))


def install_prefix(folder=None):
    """The prefix `cmake --install` put this plugin under, or None when the plugin lies elsewhere
    (a source tree, a profile's plugin folder, an unpacked zip)."""
    parts = os.path.normpath(folder or plugin_folder()).split(os.sep)
    if tuple(parts[-len(INSTALLED_PLUGIN_DIR):]) != INSTALLED_PLUGIN_DIR:
        return None
    return os.sep.join(parts[:-len(INSTALLED_PLUGIN_DIR)]) or os.sep


def installed_program():
    """The program path `cmake --install` recorded beside this plugin (install_paths.py), or None for a
    plugin that was not installed that way."""
    try:
        from . import install_paths
    except ImportError:
        return None
    program = getattr(install_paths, 'PROGRAM', '')
    return program or None


def configured_program():
    """The program path from the Processing setting, '' when unset."""
    value = QgsSettings().value(_SETTINGS_KEY, '')
    return str(value or '').strip()


def _unusable(path):
    """Why `path` cannot be the program, or None when it is an executable file."""
    if not os.path.exists(path):
        return '{} does not exist'.format(path)
    if not os.path.isfile(path):
        return '{} is not a file'.format(path)
    if not os.access(path, os.X_OK):
        return '{} is not executable'.format(path)
    return None


def _candidates():
    """(place, path, why there is no path) in search order: the setting, the install prefix, PATH."""
    configured = configured_program()
    setting = 'the plugin setting ({})'.format(SETTING_PLACE)
    if configured:
        yield setting, os.path.abspath(os.path.expanduser(configured)), None
    else:
        yield setting, None, 'not set'
    installed = installed_program()
    prefix = install_prefix()
    if installed:
        yield 'the install prefix {}'.format(os.path.dirname(os.path.dirname(installed))), installed, None
    elif prefix:
        yield 'the install prefix {}'.format(prefix), os.path.join(prefix, 'bin', 'urbanvec'), None
    else:
        yield 'the install prefix', None, 'none, this plugin ({}) was not installed by cmake --install'.format(
            plugin_folder())
    search_path = os.environ.get('PATH', '')
    on_path = shutil.which('urbanvec', path=search_path)
    yield 'PATH ({})'.format(search_path), on_path and os.path.abspath(on_path), 'no urbanvec in its folders'


def not_found_message(looked):
    """The one message shown when no candidate works; `looked` holds one line per place looked at."""
    return ('No usable urbanvec program was found, so the urbanvec provider has no algorithms. '
            'Looked in this order:\n' + ''.join('  {}. {}\n'.format(i + 1, line) for i, line in enumerate(looked)) +
            'To fix it, set the path of the urbanvec program in {}, or put the folder that holds urbanvec on PATH '
            'and restart QGIS.'.format(SETTING_PLACE))


def resolve(cache_file=None):
    """The program to run and its usage document: the first of the Processing setting, the install
    prefix (<prefix>/bin/urbanvec next to a CMake-installed plugin) and PATH that is an executable
    answering `--json-usage`.

    Returns (program, usage, skipped): `skipped` names the candidates that were set but did not work.
    Raises ProgramNotFound with not_found_message() when none works.
    """
    looked, skipped = [], []
    for place, path, why_none in _candidates():
        if path is None:
            looked.append('{}: {}'.format(place, why_none))
            continue
        problem = _unusable(path)
        if problem is None:
            try:
                usage, _ = load_usage(path, cache_file)
                return path, usage, skipped
            except ProgramNotFound as e:
                problem = str(e)
        looked.append('{}: {}'.format(place, problem))
        skipped.append(looked[-1])
    raise ProgramNotFound(not_found_message(looked))


def find_program():
    """The program to run (see resolve()); raises ProgramNotFound naming every place looked at."""
    return resolve()[0]


def cache_path():
    return os.path.join(QgsApplication.qgisSettingsDirPath(), 'processing', 'urbanvec_usage_cache.json')


def _program_key(program):
    st = os.stat(program)
    return {'path': os.path.realpath(program), 'mtime_ns': st.st_mtime_ns, 'size': st.st_size,
            'format': _CACHE_FORMAT}


def run_json_usage(program):
    """Runs `<program> --json-usage` and returns the parsed document."""
    try:
        completed = subprocess.run([program, '--json-usage'], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   timeout=_USAGE_TIMEOUT, check=False)
    except (OSError, subprocess.TimeoutExpired) as e:
        raise ProgramNotFound('cannot run {} --json-usage: {}'.format(program, e))
    if completed.returncode != 0:
        said = ' '.join(completed.stderr.decode('utf-8', 'replace').split())
        raise ProgramNotFound('{} --json-usage failed (exit status {}){}'.format(
            program, completed.returncode, ': ' + said if said else ''))
    try:
        document = json.loads(completed.stdout.decode('utf-8'))
    except ValueError as e:
        raise ProgramNotFound('{} --json-usage printed invalid JSON: {}'.format(program, e))
    if not isinstance(document, dict) or not isinstance(document.get('commands'), list):
        raise ProgramNotFound('{} --json-usage has no "commands" list'.format(program))
    return document


def load_usage(program, cache_file=None):
    """The usage document of `program`, from the cache when the program has not changed.

    Returns (document, from_cache).
    """
    cache_file = cache_file or cache_path()
    key = _program_key(program)
    try:
        with open(cache_file, 'r', encoding='utf-8') as f:
            cached = json.load(f)
        if cached.get('key') == key:
            return cached['usage'], True
    except (OSError, ValueError, KeyError, AttributeError):
        pass
    document = run_json_usage(program)
    try:
        os.makedirs(os.path.dirname(cache_file), exist_ok=True)
        temporary = cache_file + '.tmp-{}'.format(os.getpid())
        with open(temporary, 'w', encoding='utf-8') as f:
            json.dump({'key': key, 'usage': document}, f)
        os.replace(temporary, cache_file)
    except OSError:
        pass  # an unwritable profile only costs start-up time
    return document, False
