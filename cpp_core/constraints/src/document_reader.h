// Reads a parsed JSON tree as a constraint document, recording every rule it breaks.
#pragma once

#include "json_checks.h"

namespace meshik::constraints {

// The document in `top` (any JSON value) with `source` as its name. Every violated rule is added
// to `problems`; the document is complete only when no problem was added. Elements at fault are
// skipped, and rules that depend on them (a frame naming a group whose definition is bad) are not
// checked, so that one mistake gives one message.
ConstraintDocument read_document(const JsonValue& top, const std::string& source, ViolationList& problems);

// "<source>: <path or 'top level'>: <problem>", the message of one violation.
std::string violation_message(const std::string& source, const Violation& violation);

}  // namespace meshik::constraints
