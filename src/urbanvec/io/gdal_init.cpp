#include "urbanvec/io/gdal_init.hpp"

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_api.h>

#include <mutex>

namespace urbanvec::io {

namespace {
void CPL_STDCALL quietHandler(CPLErr, CPLErrorNum, const char*) {}
}  // namespace

void ensureGdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(quietHandler);
  });
}

const char* lastGdalMessage() { return CPLGetLastErrorMsg(); }

}  // namespace urbanvec::io
