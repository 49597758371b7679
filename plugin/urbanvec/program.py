"""Finding the `urbanvec` program and reading its machine-readable usage.

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


def _is_executable(path):
    return bool(path) and os.path.isfile(path) and os.access(path, os.X_OK)


def installed_candidates():
    """Where `cmake --install` puts the program, seen from where it put this plugin.

    The plugin lives in <prefix>/share/qgis/python/plugins/urbanvec, the program in <prefix>/bin.
    """
    here = os.path.dirname(os.path.abspath(__file__))
    prefix = os.path.normpath(os.path.join(here, *([os.pardir] * 5)))
    candidates = [os.path.join(prefix, 'bin', 'urbanvec'), '/usr/local/bin/urbanvec', '/usr/bin/urbanvec']
    unique = []
    for c in candidates:
        if c not in unique:
            unique.append(c)
    return unique


def configured_program():
    """The program path from the Processing setting, '' when unset."""
    value = QgsSettings().value(_SETTINGS_KEY, '')
    return str(value or '').strip()


def find_program():
    """The program to run: the Processing setting, else PATH, else the installed location.

    Raises ProgramNotFound with a sentence naming every place looked at.
    """
    configured = configured_program()
    if configured:
        if _is_executable(configured):
            return os.path.abspath(configured)
        raise ProgramNotFound(
            'the urbanvec program set in Processing options ({}) does not exist or is not executable'.format(
                configured))
    on_path = shutil.which('urbanvec')
    if on_path:
        return os.path.abspath(on_path)
    for candidate in installed_candidates():
        if _is_executable(candidate):
            return candidate
    raise ProgramNotFound(
        'the urbanvec program was not found: set its path in Settings > Options > Processing > Providers > '
        'urbanvec, or put it on PATH (looked in PATH and {})'.format(', '.join(installed_candidates())))


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
        raise ProgramNotFound('{} --json-usage failed (exit {}): {}'.format(
            program, completed.returncode, completed.stderr.decode('utf-8', 'replace').strip()))
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
