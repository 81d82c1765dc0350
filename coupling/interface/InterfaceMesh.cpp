#include "coupling/interface/InterfaceMesh.hpp"
