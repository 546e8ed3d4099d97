#pragma once
// A deliberate upward include: core may not include render. The layering
// check must reject this tree (tests/CMakeLists.txt, Architecture.*).
#include "obscura/render/renderer.h"
