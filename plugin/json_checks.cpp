#include "json_checks.h"

#include <QRegularExpression>

#include <cmath>

namespace meshik::plugin {

SchemaViolation::SchemaViolation(const QString& path_, const QString& problem_)
    : std::runtime_error((path_.isEmpty() ? problem_ : path_ + ": " + problem_).toStdString()),
      path(path_),
      problem(problem_) {}

QString childPath(const QString& path, const QString& key) {
  static const QRegularExpression identifier(QStringLiteral("^[A-Za-z_][A-Za-z0-9_\\-]*$"));
  if (identifier.match(key).hasMatch()) return path.isEmpty() ? key : path + "." + key;
  QString quoted = key;
  quoted.replace("\\", "\\\\").replace("\"", "\\\"");
  return path + "[\"" + quoted + "\"]";
}

QString childPath(const QString& path, int index) { return QStringLiteral("%1[%2]").arg(path).arg(index); }

QString describe(const QJsonValue& value) {
  switch (value.type()) {
    case QJsonValue::Null: return QStringLiteral("null");
    case QJsonValue::Bool: return value.toBool() ? QStringLiteral("true") : QStringLiteral("false");
    case QJsonValue::Double: return QStringLiteral("the number %1").arg(value.toDouble());
    case QJsonValue::String: {
      const QString text = value.toString();
      return text.size() <= 40 ? "\"" + text + "\"" : QStringLiteral("a long string");
    }
    case QJsonValue::Array: return QStringLiteral("a list of %1").arg(value.toArray().size());
    case QJsonValue::Object: return QStringLiteral("an object");
    default: return QStringLiteral("nothing");
  }
}

QJsonObject expectObject(const QJsonValue& value, const QString& path) {
  if (!value.isObject()) throw SchemaViolation(path, "expected an object, got " + describe(value));
  return value.toObject();
}

QJsonArray expectList(const QJsonValue& value, const QString& path, bool non_empty) {
  if (!value.isArray()) throw SchemaViolation(path, "expected a list, got " + describe(value));
  if (non_empty && value.toArray().isEmpty())
    throw SchemaViolation(path, QStringLiteral("expected a non-empty list"));
  return value.toArray();
}

QString expectString(const QJsonValue& value, const QString& path) {
  if (!value.isString()) throw SchemaViolation(path, "expected a string, got " + describe(value));
  if (value.toString().trimmed().isEmpty())
    throw SchemaViolation(path, QStringLiteral("expected a non-empty string"));
  return value.toString();
}

double expectNumber(const QJsonValue& value, const QString& path, double minimum, bool exclusive_minimum) {
  if (!value.isDouble()) throw SchemaViolation(path, "expected a number, got " + describe(value));
  const double number = value.toDouble();
  if (!std::isfinite(number)) throw SchemaViolation(path, QStringLiteral("expected a finite number"));
  if (number < minimum || (exclusive_minimum && number == minimum))
    throw SchemaViolation(path, QStringLiteral("expected a number %1 %2, got %3")
                                    .arg(exclusive_minimum ? ">" : ">=")
                                    .arg(minimum)
                                    .arg(number));
  return number;
}

int expectInt(const QJsonValue& value, const QString& path, int minimum, const QString& what) {
  const double number = value.isDouble() ? value.toDouble() : std::nan("");
  if (!std::isfinite(number) || number != std::floor(number) || std::fabs(number) > 2147483647.0)
    throw SchemaViolation(path, "expected " + what + ", got " + describe(value));
  if (number < minimum)
    throw SchemaViolation(path,
                          QStringLiteral("expected %1 >= %2, got %3").arg(what).arg(minimum).arg(number));
  return static_cast<int>(number);
}

void checkMembers(const QJsonObject& object, const QString& path, const QStringList& required,
                  const QStringList& optional) {
  for (const QString& name : required)
    if (!object.contains(name)) throw SchemaViolation(path, "missing member \"" + name + "\"");
  QStringList allowed = required + optional;
  allowed.sort();
  for (const QString& name : object.keys()) {
    if (!allowed.contains(name) && !name.startsWith('_'))
      throw SchemaViolation(childPath(path, name),
                            "unknown member (expected one of: " + allowed.join(", ") + ")");
  }
}

}  // namespace meshik::plugin
