#include "pose_options.h"

#include <common/mlexception.h>
#include <common/parameters/rich_parameters.h>

#include <QStringList>

#include "meshik/option_names.h"

#include <cmath>
#include <optional>

namespace meshik::plugin {
namespace {

// A number parameter's value for "from the constraint file".
constexpr int kFromFile = -1;
// The enum entry for "from the constraint file" of "featurespace" and "blend" (after the two choices).
constexpr int kFromFileEntry = 2;

// The tooltip sentence for a number parameter's default: `field` is the file's key, `fallback` the
// value without one.
QString fromFileHint(const QString& field, const QString& fallback) {
  return QStringLiteral(" -1 (the default): the constraint file's \"%1\" when the handle targets come from a "
                        "constraint file that sets it, else %2. Any other value overrides the file.")
      .arg(field, fallback);
}

// Adds the number parameter `name` (-1 by default: the constraint file's `field`, else `fallback`);
// `meaning` starts its tooltip.
void addFromFileNumber(RichParameterList& parameters, const char* name, const char* label, const QString& meaning,
                       const char* field, const char* fallback) {
  parameters.addParam(RichFloat(name, -1.0f, label, meaning + fromFileHint(field, fallback)));
}

// Collects "name value (origin)" entries for the log line.
class OptionLog {
 public:
  // `parameter`, or when the parameter says "from the constraint file" (from_file) the file's value
  // if it has one, else `fallback`. Logs `name` with the chosen value as `text` writes it (a QString).
  template <typename T, typename Text>
  T choose(const char* name, bool from_file, T parameter, const std::optional<T>& file, T fallback, Text text) {
    const char* origin = "parameter";
    T value = parameter;
    if (from_file) {
      origin = file ? "constraint file" : "default";
      value = file ? *file : fallback;
    }
    entries_ << QStringLiteral("%1 %2 (%3)").arg(name, text(value), origin);
    return value;
  }
  QString text() const { return entries_.join(", "); }

 private:
  QStringList entries_;
};

// The value of the number parameter `name`: -1 or a finite number >= 0, else throws.
double numberParameter(const RichParameterList& parameters, const char* name) {
  const double value = parameters.getFloat(name);
  if (value != kFromFile && !(std::isfinite(value) && value >= 0.0))
    throw MLException(
        QStringLiteral("%1: expected -1 (from the constraint file) or a finite number >= 0, got %2")
            .arg(name)
            .arg(value));
  return value;
}

QString numberText(double value) { return QString::number(value, 'g', 6); }

}  // namespace

void addSolverOptionParameters(RichParameterList& parameters) {
  parameters.addParam(RichInt(
      "iterations", -1, "Maximum iterations",
      "Gauss-Newton stops after this many iterations, or earlier when the energy no longer decreases "
      "(relative change below 1e-10, or the constraint file's \"tolerance\")." +
          fromFileHint("max_iterations", "30")));
  addFromFileNumber(parameters, "weightregularization", "Weight regularization",
                    "k in the energy |G'x - (M(w) + c)|^2 + k |w|^2: values above 0 pull the example weights "
                    "towards 0 (the rest pose) when the handles leave the span of the examples.",
                    "weight_regularization", "0");
  parameters.addParam(RichEnum(
      "blend", kFromFileEntry, QStringList{"Affine", "Free", "From the constraint file"}, "Stretch blend",
      "How the examples' stretches combine. Affine: tied to the rest pose, I + sum w_i (S_i - I). "
      "Free: the paper's own sum w_i S_i, not tied to the rest pose. From the constraint file (the "
      "default): the file's \"blend\" when the handle targets come from a constraint file that sets it, "
      "else Affine."));
  parameters.addParam(RichInt(
      "regions", -1, "Regions",
      "Spatially varying weights: 1 = one weight vector for the whole mesh; N >= 2 = one per region, N regions "
      "clustered from how the examples deform (so legs can take one example's stride and the body another's), "
      "blended smoothly across their borders; 0 = the count chosen from the examples." +
          fromFileHint("regions", "1") +
          " A constraint file whose regions are vertex groups gives one region per group instead (and one for "
          "the vertices in none)."));
  addFromFileNumber(parameters, "regionsmoothness", "Region smoothness",
                    "Pull between neighbouring regions' weights (with few handles it makes them one global "
                    "vector).",
                    "region_smoothness", "0.01");
  addFromFileNumber(parameters, "handlestiffness", "Handle stiffness",
                    "0 = hard handles (met exactly); > 0 = soft handles, each pulled towards its target with "
                    "this stiffness.",
                    "handle_stiffness", "0 (hard handles)");
}

ChosenSolverOptions chooseSolverOptions(const RichParameterList& parameters, const FileSolverOptions& file) {
  const SolverOptions defaults;
  const int iterations = parameters.getInt("iterations");
  if (iterations != kFromFile && iterations < 1)
    throw MLException("iterations: expected -1 (from the constraint file) or a count of at least 1");
  const int regions = parameters.getInt("regions");
  if (regions < -1)
    throw MLException("regions: expected -1 (from the constraint file), 0 (automatic) or a count of at least 1");
  const double weight_regularization = numberParameter(parameters, "weightregularization");
  const double region_smoothness = numberParameter(parameters, "regionsmoothness");
  const double handle_stiffness = numberParameter(parameters, "handlestiffness");
  const int feature_space = parameters.getEnum("featurespace");
  const int blend = parameters.getEnum("blend");

  OptionLog log;
  ChosenSolverOptions chosen;
  SolverOptions& options = chosen.options;
  options.feature_space = log.choose(
      "feature space", feature_space == kFromFileEntry,
      feature_space == 1 ? FeatureSpace::kLinear : FeatureSpace::kNonlinear, file.feature_space,
      defaults.feature_space,
      [](FeatureSpace f) { return QString(feature_space_name(f)); });
  options.blend = log.choose("blend", blend == kFromFileEntry, blend == 1 ? Blend::kFree : Blend::kAffine, file.blend,
                             defaults.blend, [](Blend b) { return QString(blend_name(b)); });
  options.regions =
      log.choose("regions", regions == kFromFile, regions == 0 ? kAutomaticRegions : regions, file.regions,
                 defaults.regions, [](int r) { return r == kAutomaticRegions ? QString("auto") : QString::number(r); });
  options.region_smoothness = log.choose("region smoothness", region_smoothness == kFromFile, region_smoothness,
                                         file.region_smoothness, defaults.region_smoothness, numberText);
  options.weight_regularization =
      log.choose("weight regularization", weight_regularization == kFromFile, weight_regularization,
                 file.weight_regularization, defaults.weight_regularization, numberText);
  options.handle_stiffness = log.choose("handle stiffness", handle_stiffness == kFromFile, handle_stiffness,
                                        file.handle_stiffness, defaults.handle_stiffness, numberText);
  options.max_iterations = log.choose("iterations", iterations == kFromFile, iterations, file.max_iterations,
                                      defaults.max_iterations, [](int n) { return QString::number(n); });
  options.tolerance =
      log.choose("tolerance", true, defaults.tolerance, file.tolerance, defaults.tolerance, numberText);
  chosen.description = log.text();
  return chosen;
}

}  // namespace meshik::plugin
