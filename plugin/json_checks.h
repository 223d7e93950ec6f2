// Small type checks for a hand-validated JSON document (QtCore's QJsonValue), with messages that
// name the JSON path the way a user points at an element: `frames[3].targets.head` or
// `handles["left foot"][2]`. The same paths and wording as the Python pipeline's json_checks.
#pragma once

#include <QJsonArray>
#include <QJsonObject>
#include <QJsonValue>
#include <QString>
#include <QStringList>

#include <array>
#include <limits>
#include <stdexcept>

namespace meshik::plugin {

// One violation: path is the JSON path of the element, problem says what is wrong.
class SchemaViolation : public std::runtime_error {
 public:
  SchemaViolation(const QString& path, const QString& problem);
  QString path;
  QString problem;
};

// The JSON path of object member `key` under `path`.
QString childPath(const QString& path, const QString& key);
// The JSON path of list element `index` under `path`.
QString childPath(const QString& path, int index);

// A short description of a JSON value for messages: "a string", "a list of 2", "null", ...
QString describe(const QJsonValue& value);

// value as an object / a list (optionally non-empty) / a non-empty string; SchemaViolation otherwise.
QJsonObject expectObject(const QJsonValue& value, const QString& path);
QJsonArray expectList(const QJsonValue& value, const QString& path, bool non_empty = false);
QString expectString(const QJsonValue& value, const QString& path);

// value as a finite number >= minimum (> minimum when exclusive_minimum); SchemaViolation otherwise.
double expectNumber(const QJsonValue& value, const QString& path,
                    double minimum = -std::numeric_limits<double>::infinity(),
                    bool exclusive_minimum = false);

// value as an integer >= minimum (no fraction); `what` names it in the message ("a vertex index").
int expectInt(const QJsonValue& value, const QString& path, int minimum,
              const QString& what = QStringLiteral("an integer"));

// value as exactly N finite numbers, e.g. a position [x, y, z].
template <int N>
std::array<double, N> expectNumbers(const QJsonValue& value, const QString& path) {
  if (!value.isArray() || value.toArray().size() != N)
    throw SchemaViolation(path, QStringLiteral("expected %1 numbers, got %2").arg(N).arg(describe(value)));
  const QJsonArray list = value.toArray();
  std::array<double, N> numbers{};
  for (int i = 0; i < N; ++i) numbers[i] = expectNumber(list[i], childPath(path, i));
  return numbers;
}

// SchemaViolation when a required member is missing or a member is neither required nor
// optional (members starting with '_' are the user's annotations and always allowed).
void checkMembers(const QJsonObject& object, const QString& path, const QStringList& required,
                  const QStringList& optional);

}  // namespace meshik::plugin
