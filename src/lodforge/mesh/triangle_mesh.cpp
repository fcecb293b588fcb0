#include "lodforge/mesh/triangle_mesh.h"
