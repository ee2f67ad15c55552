// NRRD (teem's "nearly raw raster data"): a text header of "field: value" lines, then the data, either
// attached after a blank line (.nrrd) or in the file named by "data file:" (.nhdr). Only what a 3-D scalar
// volume needs is interpreted; other fields (kinds, units, key:=value pairs, ...) are skipped.
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include "ByteSource.h"
#include "DenseSource.h"
#include "MessageText.h"
#include "StoredVoxels.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

// A real header is a few hundred bytes; these bounds stop a binary file posing as one early.
constexpr size_t kMaxHeaderLineBytes = 64 * 1024;
constexpr uint64_t kMaxHeaderBytes = 1 << 20;

struct TypeSpelling {
  const char* name;
  ScalarType type;
};

// Every spelling the NRRD format defines for the eight supported types.
constexpr TypeSpelling kTypeSpellings[] = {
    {"signed char", ScalarType::I8},    {"int8", ScalarType::I8},
    {"int8_t", ScalarType::I8},         {"uchar", ScalarType::U8},
    {"unsigned char", ScalarType::U8},  {"uint8", ScalarType::U8},
    {"uint8_t", ScalarType::U8},        {"short", ScalarType::I16},
    {"short int", ScalarType::I16},     {"signed short", ScalarType::I16},
    {"signed short int", ScalarType::I16}, {"int16", ScalarType::I16},
    {"int16_t", ScalarType::I16},       {"ushort", ScalarType::U16},
    {"unsigned short", ScalarType::U16}, {"unsigned short int", ScalarType::U16},
    {"uint16", ScalarType::U16},        {"uint16_t", ScalarType::U16},
    {"int", ScalarType::I32},           {"signed int", ScalarType::I32},
    {"int32", ScalarType::I32},         {"int32_t", ScalarType::I32},
    {"uint", ScalarType::U32},          {"unsigned int", ScalarType::U32},
    {"uint32", ScalarType::U32},        {"uint32_t", ScalarType::U32},
    {"float", ScalarType::F32},         {"double", ScalarType::F64},
};

struct Field {
  std::string value;
  int line = 0;
};

// The header as read: its fields by (lowercase) name, and where attached data would start.
struct NrrdHeader {
  std::map<std::string, Field> fields;
  uint64_t end = 0;             // byte after the header
  bool endsWithBlankLine = false;  // only then can data be attached
};

std::string trim(std::string_view text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const size_t last = text.find_last_not_of(" \t");
  return std::string(text.substr(first, last - first + 1));
}

// Lowercase with runs of blanks made single spaces, so "unsigned  Short" matches "unsigned short".
std::string normalized(std::string_view text) {
  std::string out;
  for (const char c : trim(text)) {
    if (c == ' ' || c == '\t') {
      if (out.empty() || out.back() != ' ') out += ' ';
    } else {
      out += char(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  return out;
}

std::vector<std::string> splitBlanks(std::string_view text) {
  std::vector<std::string> words;
  size_t at = 0;
  while (at < text.size()) {
    const size_t start = text.find_first_not_of(" \t", at);
    if (start == std::string_view::npos) break;
    const size_t stop = std::min(text.size(), text.find_first_of(" \t", start));
    words.emplace_back(text.substr(start, stop - start));
    at = stop;
  }
  return words;
}

std::optional<double> parseDouble(std::string_view text) {
  std::string word = trim(text);
  if (!word.empty() && word[0] == '+') word.erase(0, 1);  // from_chars rejects a leading '+'
  double value = 0.0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (word.empty() || error != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return value;
}

std::optional<long long> parseInteger(std::string_view text) {
  std::string word = trim(text);
  if (!word.empty() && word[0] == '+') word.erase(0, 1);
  long long value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (word.empty() || error != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return value;
}

class HeaderParser {
 public:
  explicit HeaderParser(const std::string& path) : path_(path) {}

  [[noreturn]] void fail(const Field& field, const std::string& what) const {
    throw InputError(path_ + ": line " + std::to_string(field.line) + ": " + what);
  }

  NrrdHeader read() const {
    ByteSource source(path_, 0, Compression::Plain);
    char magic[7] = {};
    const size_t got = source.read(magic, sizeof magic);
    if (std::string_view(magic, got) != "NRRD000")
      throw InputError(path_ + ": not a NRRD file: it starts with " + quotedText(std::string_view(magic, got)) +
                       ", a NRRD header starts with \"NRRD000\" and a version digit (e.g. NRRD0004)");
    std::string line;
    source.readLine(line, kMaxHeaderLineBytes);
    if (line.size() != 1 || line[0] < '1' || line[0] > '9')
      throw InputError(path_ + ": line 1: magic " + quotedText("NRRD000" + line) + " is not \"NRRD000\" and a version digit");

    NrrdHeader header;
    for (int number = 2;; ++number) {
      if (!source.readLine(line, kMaxHeaderLineBytes)) break;
      if (source.position() > kMaxHeaderBytes)
        throw InputError(path_ + ": header is longer than " + std::to_string(kMaxHeaderBytes) +
                         " bytes without the blank line that ends it; this is not a NRRD header");
      if (line.empty()) {
        header.endsWithBlankLine = true;
        break;
      }
      if (line[0] == '#') continue;
      const size_t colon = line.find(':');
      if (colon == std::string::npos || colon == 0)
        fail({line, number}, "expected \"field: value\" or a \"#\" comment, found " + quotedText(line));
      if (colon + 1 < line.size() && line[colon + 1] == '=') continue;  // "key:=value": user data, not ours
      const std::string name = normalized(line.substr(0, colon));
      Field& field = header.fields[name] = Field{trim(std::string_view(line).substr(colon + 1)), number};
      // "data file: LIST" is followed by data file names, one per line, to the end of the header.
      if ((name == "data file" || name == "datafile") && field.value.rfind("LIST", 0) == 0) break;
    }
    header.end = source.position();
    return header;
  }

 private:
  const std::string& path_;
};

// One entry of a "space directions" or "space origin" field: "(x,y,z)", or "none" for a non-spatial axis.
using SpaceVector = std::optional<std::vector<double>>;

std::vector<SpaceVector> parseSpaceVectors(const Field& field, const HeaderParser& parser) {
  std::vector<SpaceVector> vectors;
  const std::string& text = field.value;
  size_t at = 0;
  for (;;) {
    at = text.find_first_not_of(" \t", at);
    if (at == std::string::npos) return vectors;
    if (text.compare(at, 4, "none") == 0) {
      vectors.emplace_back(std::nullopt);
      at += 4;
      continue;
    }
    const size_t close = text.find(')', at);
    if (text[at] != '(' || close == std::string::npos)
      parser.fail(field, "expected vectors like \"(1,0,0)\" or \"none\", found " + quotedText(text));
    std::vector<double> components;
    size_t start = at + 1;
    for (;;) {
      const size_t comma = std::min(close, text.find(',', start));
      const std::optional<double> value = parseDouble(std::string_view(text).substr(start, comma - start));
      if (!value || !std::isfinite(*value))
        parser.fail(field, "vector component " + quotedText(text.substr(start, comma - start)) + " is not a finite number");
      components.push_back(*value);
      if (comma == close) break;
      start = comma + 1;
    }
    if (components.size() != 3)
      parser.fail(field, "vector " + quotedText(text.substr(at, close + 1 - at)) +
                             " has " + std::to_string(components.size()) + " components; only 3-D space is supported");
    vectors.emplace_back(std::move(components));
    at = close + 1;
  }
}

ScalarType parseType(const Field& field, const HeaderParser& parser) {
  const std::string name = normalized(field.value);
  for (const TypeSpelling& spelling : kTypeSpellings)
    if (name == spelling.name) return spelling.type;
  parser.fail(field, "type " + quotedText(field.value) +
                         " is not supported; valid: int8, uint8, int16, uint16, int32, uint32, float, double "
                         "(or a C spelling such as \"unsigned short\")");
}

glm::ivec3 parseSizes(const Field& field, const HeaderParser& parser) {
  const std::vector<std::string> words = splitBlanks(field.value);
  if (words.size() != 3) parser.fail(field, "sizes " + quotedText(field.value) + " must be 3 numbers for a 3-D volume");
  glm::ivec3 dims(0);
  for (int axis = 0; axis < 3; ++axis) {
    const std::optional<long long> size = parseInteger(words[axis]);
    if (!size || *size < 1 || *size > std::numeric_limits<int>::max())
      parser.fail(field, "size " + quotedText(words[axis]) + " must be a whole number from 1 to " +
                             std::to_string(std::numeric_limits<int>::max()));
    dims[axis] = int(*size);
  }
  return dims;
}

// From "space directions" when present (the magnitude of each axis-aligned vector, its sign into
// `signs`), else "spacings"; unknown spacings ("nan", "none") are 1.
glm::dvec3 parseSpacing(const NrrdHeader& header, const HeaderParser& parser, glm::dvec3& signs) {
  glm::dvec3 spacing(1.0);
  signs = glm::dvec3(1.0);
  if (auto directions = header.fields.find("space directions"); directions != header.fields.end()) {
    const Field& field = directions->second;
    const std::vector<SpaceVector> vectors = parseSpaceVectors(field, parser);
    if (vectors.size() != 3) parser.fail(field, "space directions must list 3 vectors, one per axis");
    for (int axis = 0; axis < 3; ++axis) {
      if (!vectors[axis]) continue;
      const std::vector<double>& v = *vectors[axis];
      const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      // The volume keeps spacing and origin only, so axis i must run along world axis i (either way).
      for (int other = 0; other < 3; ++other)
        if (other != axis && std::abs(v[other]) > 1e-6 * length)
          parser.fail(field, "space directions are not axis-aligned (axis " + std::to_string(axis) + " is (" +
                                 numberText(v[0]) + "," + numberText(v[1]) + "," + numberText(v[2]) +
                                 ")); only diagonal directions are supported");
      if (v[axis] == 0.0) parser.fail(field, "space direction of axis " + std::to_string(axis) + " is zero");
      spacing[axis] = std::abs(v[axis]);
      signs[axis] = v[axis] < 0.0 ? -1.0 : 1.0;
    }
  } else if (auto spacings = header.fields.find("spacings"); spacings != header.fields.end()) {
    const Field& field = spacings->second;
    const std::vector<std::string> words = splitBlanks(field.value);
    if (words.size() != 3) parser.fail(field, "spacings " + quotedText(field.value) + " must be 3 numbers");
    for (int axis = 0; axis < 3; ++axis) {
      const std::optional<double> value = parseDouble(words[axis]);
      if (!value) parser.fail(field, "spacing " + quotedText(words[axis]) + " is not a number");
      if (std::isnan(*value)) continue;
      if (*value == 0.0 || !std::isfinite(*value))
        parser.fail(field, "spacing " + quotedText(words[axis]) + " must be nonzero and finite (or nan when unknown)");
      spacing[axis] = std::abs(*value);
    }
  }
  return spacing;
}

glm::dvec3 parseOrigin(const NrrdHeader& header, const HeaderParser& parser) {
  auto origin = header.fields.find("space origin");
  if (origin == header.fields.end()) return glm::dvec3(0.0);
  const std::vector<SpaceVector> vectors = parseSpaceVectors(origin->second, parser);
  if (vectors.size() != 1 || !vectors[0]) parser.fail(origin->second, "space origin must be one vector like \"(0,0,0)\"");
  return glm::dvec3((*vectors[0])[0], (*vectors[0])[1], (*vectors[0])[2]);
}

// An anatomical "space" (NRRD's three, long or short names) gives the patient's axes: index axis i runs
// along space axis i, the way `signs` says, while the world keeps it running forward (spacing is the
// magnitude). Other spaces ("scanner-xyz", "3D-right-handed", ...) and none give none.
std::optional<PatientAxes> parsePatient(const NrrdHeader& header, const glm::dvec3& signs) {
  const auto space = header.fields.find("space");
  if (space == header.fields.end()) return std::nullopt;
  const std::string name = normalized(space->second.value);
  glm::dvec3 anterior;
  if (name == "right-anterior-superior" || name == "ras" || name == "left-anterior-superior" || name == "las")
    anterior = kAnteriorInRas;
  else if (name == "left-posterior-superior" || name == "lps")
    anterior = kAnteriorInLps;
  else
    return std::nullopt;
  const glm::dmat3 spaceFromWorld(glm::dvec3(signs.x, 0, 0), glm::dvec3(0, signs.y, 0), glm::dvec3(0, 0, signs.z));
  return patientAxesFrom(spaceFromWorld, kSuperiorInPatient, anterior);
}

const Field* findField(const NrrdHeader& header, std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (auto found = header.fields.find(name); found != header.fields.end()) return &found->second;
  return nullptr;
}

const Field& requireField(const NrrdHeader& header, const char* name, const std::string& path) {
  const Field* field = findField(header, {name});
  if (field == nullptr) throw InputError(path + ": missing required field \"" + name + ":\"");
  return *field;
}

long long parseSkip(const Field* field, const char* name, long long lowest, const HeaderParser& parser) {
  if (field == nullptr) return 0;
  const std::optional<long long> value = parseInteger(field->value);
  if (!value || *value < lowest)
    parser.fail(*field, std::string(name) + " " + quotedText(field->value) + " must be a whole number >= " + std::to_string(lowest));
  return *value;
}

// Skips `lines` newline-terminated lines of the data file as stored ("line skip" counts before decoding).
void skipLines(ByteSource& source, long long lines, const std::string& headerPath) {
  for (long long line = 0; line < lines; ++line) {
    char c = 0;
    do {
      if (source.read(&c, 1) != 1)
        throw InputError(source.path() + ": data ends before the " + std::to_string(lines) +
                         " lines that \"line skip\" in " + headerPath + " says to skip");
    } while (c != '\n');
  }
}

// Data that ends before the voxels do: `holds` bytes after the byte skip.
InputError dataSizeError(const std::string& dataLabel, bool gzip, long long byteSkip, const glm::ivec3& dims,
                         ScalarType type, uint64_t payload, uint64_t holds) {
  return InputError(dataLabel + ": data holds " + std::to_string(holds) + " bytes" + (gzip ? " once decompressed" : "") +
                    (byteSkip != 0 ? " after byte skip " + std::to_string(byteSkip) : std::string()) + " but sizes " +
                    commaList(dims) + " of type " + scalarTypeName(type) + " need " + std::to_string(payload));
}

}  // namespace

std::unique_ptr<DenseSource> openNrrd(const std::string& path) {
  const HeaderParser parser(path);
  const NrrdHeader header = parser.read();

  const Field& dimension = requireField(header, "dimension", path);
  if (parseInteger(dimension.value) != 3)
    parser.fail(dimension, "dimension " + quotedText(dimension.value) + " is not supported; only 3-D volumes (dimension: 3)");
  const ScalarType type = parseType(requireField(header, "type", path), parser);
  const glm::ivec3 dims = parseSizes(requireField(header, "sizes", path), parser);
  const Field& encodingField = requireField(header, "encoding", path);
  const std::string encoding = normalized(encodingField.value);
  if (encoding != "raw" && encoding != "gzip" && encoding != "gz")
    parser.fail(encodingField, "encoding " + quotedText(encodingField.value) + " is not supported; valid: raw, gzip (gz)");
  const bool gzip = encoding != "raw";

  bool bigEndian = false;
  if (scalarTypeSize(type) > 1) {
    const Field& endian = requireField(header, "endian", path);
    const std::string order = normalized(endian.value);
    if (order != "little" && order != "big") parser.fail(endian, "endian " + quotedText(endian.value) + " is not valid; valid: little, big");
    bigEndian = order == "big";
  }

  DenseVolume volume;
  volume.dims = dims;
  glm::dvec3 signs;
  volume.spacing = parseSpacing(header, parser, signs);
  volume.origin = parseOrigin(header, parser);
  volume.patient = parsePatient(header, signs);
  const uint64_t voxels = checkedVoxelCount(dims, path);
  const uint64_t payload = voxels * scalarTypeSize(type);

  // Where the data is: the named file from its start, or this file after the header's blank line.
  std::string dataPath = path;
  uint64_t dataStart = header.end;
  if (const Field* dataFile = findField(header, {"data file", "datafile"})) {
    if (dataFile->value.empty() || dataFile->value.rfind("LIST", 0) == 0 || dataFile->value.find('%') != std::string::npos)
      parser.fail(*dataFile, "data file " + quotedText(dataFile->value) + " is not supported; only one data file per volume");
    const std::filesystem::path named(dataFile->value);
    dataPath = (named.is_absolute() ? named : std::filesystem::path(path).parent_path() / named).string();
    dataStart = 0;
    // A device or a pipe (/dev/zero, /dev/stdin) would be read up to the voxel limit, or block: only
    // files on disk hold a volume's data. (A missing file is reported where it is opened.)
    std::error_code ec;
    const auto status = std::filesystem::status(dataPath, ec);
    if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
      parser.fail(*dataFile, "data file " + quotedText(dataFile->value) + " is not a regular file; the data must be in a file");
  } else if (!header.endsWithBlankLine) {
    throw InputError(path + ": header has no \"data file:\" field and no blank line before attached data");
  }
  const std::string dataLabel = dataPath == path ? path : dataPath + " (data of " + path + ")";

  const long long lineSkip = parseSkip(findField(header, {"line skip", "lineskip"}), "line skip", 0, parser);
  const Field* byteSkipField = findField(header, {"byte skip", "byteskip"});
  long long byteSkip = parseSkip(byteSkipField, "byte skip", -1, parser);
  if (lineSkip > 0) {
    ByteSource lines(dataPath, dataStart, Compression::Plain);
    skipLines(lines, lineSkip, path);
    dataStart += lines.position();
  }
  ByteSource source(dataPath, dataStart, gzip ? Compression::Gzip : Compression::Plain);

  auto sizeError = [&](uint64_t holds) { return dataSizeError(dataLabel, gzip, byteSkip, dims, type, payload, holds); };
  if (byteSkip == -1) {  // "-1": the data is the last bytes of the file, after whatever precedes it
    if (gzip) parser.fail(*byteSkipField, "byte skip -1 is only valid with encoding raw");
    if (!source.knownSize()) parser.fail(*byteSkipField, "byte skip -1 needs a regular data file of known size");
    if (*source.knownSize() < payload) throw sizeError(*source.knownSize());
    byteSkip = static_cast<long long>(*source.knownSize() - payload);
  }
  if (source.knownSize() && *source.knownSize() < uint64_t(byteSkip) + payload)
    throw sizeError(*source.knownSize() - std::min<uint64_t>(*source.knownSize(), uint64_t(byteSkip)));

  StoredVoxels stored;
  stored.path = dataPath;
  stored.fileOffset = dataStart;
  stored.gzip = gzip;
  stored.skipBytes = uint64_t(byteSkip);
  stored.type = type;
  stored.bigEndian = bigEndian;
  // The source outlives this function: it words its errors from copies.
  stored.sizeError = [=](uint64_t holds) {
    return dataSizeError(dataLabel, gzip, byteSkip, dims, type, payload, holds - std::min<uint64_t>(holds, uint64_t(byteSkip)));
  };
  return openStoredVoxels(volume, std::move(stored));
}

DenseVolume readNrrd(const std::string& path) { return readAllVoxels(*openNrrd(path)); }

}  // namespace fcc::io
