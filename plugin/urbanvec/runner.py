"""Runs the urbanvec program for an algorithm: argument list (never a shell string), progress,
warnings, cancellation and errors mapped onto QGIS Processing feedback.

QgsBlockingProcess would be the natural runner, but in QGIS 3.22 it calls its stdout/stderr handlers
from a thread of its own while the calling thread holds Python's lock, and PyQGIS crashes (segfault)
as soon as a Python handler is set. So this module drives a QProcess with the blocking API and polls
feedback.isCanceled() between reads, which works in the GUI's worker threads and in qgis_process.
"""

import glob
import os
import re
import shutil

from qgis.PyQt.QtCore import QProcess, QProcessEnvironment
from qgis.core import QgsApplication, QgsMessageLog, Qgis, QgsProcessingException

#: Milliseconds between cancellation checks while the program runs.
POLL_INTERVAL_MS = 100
#: Milliseconds the program gets to clean up after SIGTERM before it is killed.
TERMINATE_GRACE_MS = 10000
#: Milliseconds allowed for the program to start.
START_TIMEOUT_MS = 30000

EXIT_CANCELLED = 3

_PROGRESS = re.compile(r'^PROGRESS\s+([0-9]+(?:\.[0-9]*)?)(?:\s+(.*))?$')
_ERROR = re.compile(r'^ERROR(?:\s+\d+)?:\s*(.*)$')
_WARNING = re.compile(r'^Warning(?:\s+\d+)?:\s*(.*)$')


def parse_progress(line):
    """(percent, stage) of a `PROGRESS <percent> <stage>` line (percent at most 100, stage as words
    separated by single spaces, '' when absent), or None for any other line."""
    match = _PROGRESS.match(line)
    if not match:
        return None
    return min(100.0, float(match.group(1))), ' '.join((match.group(2) or '').split())


def on_console():
    """True inside qgis_process, whose feedback prints progress as a bar of ticks ('0...10...20')
    without a newline, so that a text printed next would be glued to the last tick ('10parcels')."""
    app = QgsApplication.instance()
    return app is not None and app.platform() == 'qgis_process'


def quote_for_log(args):
    """A copy-pasteable rendering of an argument list, for the log only (never executed)."""
    out = []
    for a in args:
        if a and re.fullmatch(r'[A-Za-z0-9_@%+=:,./-]+', a):
            out.append(a)
        else:
            out.append("'" + a.replace("'", "'\"'\"'") + "'")
    return ' '.join(out)


class _LineSplitter:
    """Turns chunks of bytes into complete lines (a chunk may end mid-line)."""

    def __init__(self, on_line):
        self._buffer = b''
        self._on_line = on_line

    def feed(self, data):
        self._buffer += bytes(data)
        while True:
            cut = self._buffer.find(b'\n')
            if cut < 0:
                return
            line, self._buffer = self._buffer[:cut], self._buffer[cut + 1:]
            self._on_line(line.decode('utf-8', 'replace').rstrip('\r'))

    def flush(self):
        if self._buffer:
            line, self._buffer = self._buffer, b''
            self._on_line(line.decode('utf-8', 'replace').rstrip('\r'))


class ProgramRun:
    """One run of the program; `run()` returns the exit code or raises QgsProcessingException."""

    def __init__(self, program, arguments, feedback, temporary_outputs=(), console=None):
        self.program = program
        self.arguments = list(arguments)
        self.feedback = feedback
        #: Final output paths; after a kill, AtomicOutput's hidden temporaries beside them are removed.
        self.temporary_outputs = list(temporary_outputs)
        self.errors = []
        self.warnings = []
        self.progress = 0.0
        self.stage = ''
        self.cancelled = False
        self.terminate_grace_ms = TERMINATE_GRACE_MS
        #: Texts are given a line of their own after progress ticks (qgis_process); see on_console().
        self.console = on_console() if console is None else console
        self._ticks_on_line = False

    # -- output parsing -------------------------------------------------------------------------
    def _set_progress(self, percent):
        if self.feedback:
            self.feedback.setProgress(percent)
            self._ticks_on_line = self.console

    def _new_line(self):
        """Ends a line of progress ticks (qgis_process) so that the next text gets a line of its own."""
        if self._ticks_on_line:
            self._ticks_on_line = False
            self.feedback.pushConsoleInfo('')

    def _on_stdout(self, line):
        progress = parse_progress(line)
        if progress:
            percent, stage = progress
            if percent > self.progress:  # progress shown never goes backwards
                self.progress = percent
                self._set_progress(percent)
            if stage and stage != self.stage:
                self.stage = stage
                if self.feedback:
                    self._new_line()
                    self.feedback.setProgressText(stage)
            return
        if line.strip() and self.feedback:
            self._new_line()
            self.feedback.pushConsoleInfo(line)

    def _on_stderr(self, line):
        if not line.strip():
            return
        error = _ERROR.match(line)
        warning = _WARNING.match(line)
        if error:
            self.errors.append(error.group(1).strip())
            if self.feedback:
                self._new_line()
                self.feedback.pushConsoleInfo(line)
        elif warning:
            self.warnings.append(warning.group(1).strip())
            if self.feedback:
                self._new_line()
                self.feedback.pushWarning(warning.group(1).strip())
        elif self.feedback:
            self._new_line()
            self.feedback.pushConsoleInfo(line)

    # -- running --------------------------------------------------------------------------------
    def command_line(self):
        return quote_for_log([self.program] + self.arguments)

    def run(self):
        if self.feedback:
            self.feedback.pushCommandInfo(self.command_line())
        QgsMessageLog.logMessage(self.command_line(), 'urbanvec', Qgis.Info)

        stdout = _LineSplitter(self._on_stdout)
        stderr = _LineSplitter(self._on_stderr)
        process = QProcess()
        process.setProcessEnvironment(QProcessEnvironment.systemEnvironment())
        process.setProgram(self.program)
        process.setArguments(self.arguments)
        process.start()
        if not process.waitForStarted(START_TIMEOUT_MS):
            raise QgsProcessingException('could not start {}: {}'.format(self.program, process.errorString()))
        pid = process.processId()

        terminate_sent_at = None
        killed = False
        elapsed = 0
        while True:
            finished = process.waitForFinished(POLL_INTERVAL_MS)
            stdout.feed(process.readAllStandardOutput())
            stderr.feed(process.readAllStandardError())
            if finished or process.state() == QProcess.NotRunning:
                break
            elapsed += POLL_INTERVAL_MS
            if self.feedback and self.feedback.isCanceled() and not killed:
                if terminate_sent_at is None:
                    # SIGTERM: the program stops at its next progress check and removes its temporaries.
                    self.cancelled = True
                    terminate_sent_at = elapsed
                    process.terminate()
                elif elapsed - terminate_sent_at > self.terminate_grace_ms:
                    process.kill()
                    killed = True
        process.waitForFinished(-1)
        stdout.feed(process.readAllStandardOutput())
        stderr.feed(process.readAllStandardError())
        stdout.flush()
        stderr.flush()

        crashed = process.exitStatus() != QProcess.NormalExit
        exit_code = process.exitCode()
        if killed or crashed:
            self._remove_temporaries(pid)
        if self.cancelled or (self.feedback and self.feedback.isCanceled()):
            raise QgsProcessingException('urbanvec was cancelled; no output was written')
        if crashed:
            raise QgsProcessingException('{} crashed ({})'.format(
                os.path.basename(self.program), self.errors[-1] if self.errors else 'no error message'))
        if exit_code == EXIT_CANCELLED:
            raise QgsProcessingException('urbanvec was cancelled; no output was written')
        if exit_code != 0:
            message = self.errors[-1] if self.errors else 'urbanvec failed with exit code {}'.format(exit_code)
            raise QgsProcessingException(message)
        self._set_progress(100)
        return exit_code

    def _remove_temporaries(self, pid):
        """After a kill, removes the hidden `.<stem>.tmp-<pid><ext>` files the program left beside its outputs."""
        for output in self.temporary_outputs:
            folder = os.path.dirname(os.path.abspath(output))
            stem, extension = os.path.splitext(os.path.basename(output))
            pattern = os.path.join(folder, glob.escape('.{}.tmp-{}{}'.format(stem, pid, extension)))
            for leftover in glob.glob(pattern + '*'):
                try:
                    if os.path.isdir(leftover):
                        shutil.rmtree(leftover, ignore_errors=True)
                    else:
                        os.remove(leftover)
                except OSError:
                    pass
