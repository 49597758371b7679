"""The `urbanvec` Processing provider: one algorithm per subcommand of the program it finds."""

import os

from qgis.PyQt.QtGui import QIcon
from qgis.core import Qgis, QgsMessageLog, QgsProcessingException, QgsProcessingProvider

from .algorithm import UrbanvecAlgorithm
from .program import PROGRAM_SETTING, ProgramNotFound, find_program, load_usage

ICON = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'icon.svg')


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
                                      self.tr('urbanvec program (empty: look in PATH, then the install folder)'),
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
            self.program = find_program()
            usage, _ = load_usage(self.program)
        except ProgramNotFound as e:
            self.program = None
            self.problem = str(e)
            QgsMessageLog.logMessage(self.problem, 'urbanvec', Qgis.Warning)
            return
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
            return find_program()
        except ProgramNotFound as e:
            raise QgsProcessingException(str(e))
