"""The `urbanvec` Processing provider: one algorithm per subcommand of the program it finds."""

import os
import sys

from qgis.PyQt.QtGui import QIcon
from qgis.core import (Qgis, QgsApplication, QgsMessageLog, QgsProcessingAlgorithm, QgsProcessingException,
                       QgsProcessingProvider)

from .algorithm import UrbanvecAlgorithm
from .program import PROGRAM_SETTING, ProgramNotFound, resolve

ICON = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'icon.svg')


#: Messages already reported in this QGIS process (a refresh with the same problem says nothing new).
_reported = set()


def report(message):
    """Shows `message` once per process: in the message log (tab urbanvec) and, outside the desktop
    application (qgis_process, PyQGIS scripts), on stderr, where nobody would see the log."""
    if message in _reported:
        return
    _reported.add(message)
    QgsMessageLog.logMessage(message, 'urbanvec', Qgis.Warning)  # qgis_process echoes Critical ones
    app = QgsApplication.instance()
    if app is None or app.platform() != 'desktop':
        sys.stderr.write('urbanvec: {}\n'.format(message))
        sys.stderr.flush()


class ProgramNotFoundAlgorithm(QgsProcessingAlgorithm):
    """The provider's only entry when no program works, so the toolbox shows why it has no algorithms
    (QGIS hides a provider without algorithms). Its help is the message; running it raises it."""

    def __init__(self, message):
        super().__init__()
        self.message = message

    def createInstance(self):
        return ProgramNotFoundAlgorithm(self.message)

    def name(self):
        return 'program_not_found'

    def displayName(self):
        return 'urbanvec program not found (open for how to fix it)'

    def shortDescription(self):
        return 'No usable urbanvec program was found; open for where the plugin looked and how to fix it.'

    def shortHelpString(self):
        return self.message  # one paragraph per line in the toolbox's help panel

    def initAlgorithm(self, config=None):
        pass

    def processAlgorithm(self, parameters, context, feedback):
        raise QgsProcessingException(self.message)


def _processing_config():
    try:
        from processing.core.ProcessingConfig import ProcessingConfig, Setting, settingsWatcher
        return ProcessingConfig, Setting, settingsWatcher
    except ImportError:  # Processing's Python plugin is absent: the setting is still read from QgsSettings
        return None, None, None


class UrbanvecProvider(QgsProcessingProvider):
    def __init__(self):
        super().__init__()
        self.program = None
        self.program_version = ''
        self.problem = None

    def id(self):
        return 'urbanvec'

    def name(self):
        return 'urbanvec'

    def longName(self):
        if self.problem:
            return 'urbanvec (program not found)'
        return 'urbanvec {}'.format(self.program_version) if self.program_version else 'urbanvec'

    def versionInfo(self):
        return self.program_version

    def icon(self):
        return QIcon(ICON)

    def svgIconPath(self):
        return ICON

    def defaultVectorFileExtension(self, hasGeometry=True):
        return 'gpkg'

    def defaultRasterFileExtension(self):
        return 'tif'

    def supportsNonFileBasedOutput(self):
        return False  # the program writes files

    def supportedOutputVectorLayerExtensions(self):
        return ['gpkg']  # the program writes several layers into one dataset

    def supportedOutputRasterLayerExtensions(self):
        return ['tif']

    def load(self):
        config, setting, watcher = _processing_config()
        if config is not None:
            config.settingIcons[self.name()] = self.icon()
            config.addSetting(setting(self.name(), PROGRAM_SETTING,
                                      self.tr('urbanvec program (if empty or not working: <prefix>/bin of a CMake install, then PATH)'),
                                      '', valuetype=setting.FILE))
            config.readSettings()
            watcher.settingsChanged.connect(self.refreshAlgorithms)
        self.refreshAlgorithms()
        return True

    def unload(self):
        config, _, watcher = _processing_config()
        if config is not None:
            try:
                watcher.settingsChanged.disconnect(self.refreshAlgorithms)
            except TypeError:
                pass
            if PROGRAM_SETTING in config.settings:
                config.removeSetting(PROGRAM_SETTING)

    def loadAlgorithms(self):
        self.problem = None
        try:
            self.program, usage, skipped = resolve()
        except ProgramNotFound as e:
            self.program = None
            self.program_version = ''
            self.problem = str(e)
            report(self.problem)
            self.addAlgorithm(ProgramNotFoundAlgorithm(self.problem))
            return
        for problem in skipped:
            report('not using {}; using {}'.format(problem, self.program))
        self.program_version = usage.get('version', '')
        for command in usage.get('commands', []):
            try:
                self.addAlgorithm(UrbanvecAlgorithm(command, self.locate_program))
            except Exception as e:  # one malformed command must not hide the others
                QgsMessageLog.logMessage('cannot build the algorithm for urbanvec {}: {}'.format(
                    command.get('name', '?'), e), 'urbanvec', Qgis.Warning)

    def locate_program(self):
        """The program to run now (the setting may have changed since the algorithms were built)."""
        try:
            return resolve()[0]
        except ProgramNotFound as e:
            raise QgsProcessingException(str(e))
