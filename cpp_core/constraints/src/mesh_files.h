// The mesh files of a constraint document, for validate_constraint_file (locate_mesh_files is public).
#pragma once

#include "meshik/constraints/constraint_file.h"

#include <string>
#include <vector>

namespace meshik::constraints {

// Every missing mesh file of a document (the rest mesh, each example, an empty glob) as full
// messages, the messages locate_mesh_files raises for the first of them.
std::vector<std::string> mesh_file_problems(const ConstraintDocument& document);

}  // namespace meshik::constraints
