#include "SurfaceFiles.h"

#include "SurfaceMeshing.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <sys/stat.h>
#include <type_traits>

namespace tetmesher
{
namespace cli
{

void Fail(const std::string& path, const std::string& what)
{
  throw FileError(path + ": " + what);
}

void RequireReadableFile(const std::string& path)
{
  struct stat info;
  if (stat(path.c_str(), &info) != 0)
  {
    Fail(path, "no such file");
  }
  if (!S_ISREG(info.st_mode))
  {
    Fail(path, "not a regular file");
  }
  std::ifstream probe(path);
  if (!probe)
  {
    Fail(path, "cannot be opened for reading");
  }
  if (info.st_size == 0)
  {
    Fail(path, "the file is empty");
  }
}

std::string LowerExtension(const std::string& path)
{
  auto dot = path.rfind('.');
  auto slash = path.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return "";
  }
  return LowerCase(path.substr(dot));
}

std::string LowerCase(std::string text)
{
  std::transform(text.begin(),
    text.end(),
    text.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool ReadWholeFile(const std::string& path, std::string& text)
{
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
    return false;
  std::fseek(file, 0, SEEK_END);
  const long size = std::ftell(file);
  std::fseek(file, 0, SEEK_SET);
  text.resize(size > 0 ? static_cast<std::size_t>(size) : 0);
  const bool ok = size >= 0 && std::fread(&text[0], 1, text.size(), file) == text.size();
  std::fclose(file);
  return ok;
}

TokenFile::TokenFile(const std::string& path)
  : Path(path)
  , Stream(path)
{
}

bool TokenFile::NextLine(std::istringstream& line)
{
  std::string text;
  while (std::getline(this->Stream, text))
  {
    ++this->LineNumber;
    auto hash = text.find('#');
    if (hash != std::string::npos)
    {
      text.erase(hash);
    }
    if (text.find_first_not_of(" \t\r") == std::string::npos)
    {
      continue;
    }
    line.clear();
    line.str(text);
    return true;
  }
  return false;
}

void TokenFile::Fail(const std::string& what) const
{
  cli::Fail(this->Path, "line " + std::to_string(this->LineNumber) + ": " + what);
}

namespace
{
// The fast .off parser's view of the text: meaningful lines as TokenFile::NextLine gives them
// (split at '\n', cut at '#', skipped when only ' ', '\t', '\r'), tokens separated by those
// three. Anything else it declines.
class OffText
{
public:
  explicit OffText(const std::string& text)
    : Next(text.data())
    , End(text.data() + text.size())
  {
  }

  // Moves to the next meaningful line; false at the end of the text.
  bool NextLine()
  {
    while (Next < End)
    {
      const char* eol = static_cast<const char*>(std::memchr(Next, '\n', End - Next));
      const char* lineEnd = eol ? eol : End;
      const char* hash = static_cast<const char*>(std::memchr(Next, '#', lineEnd - Next));
      Cursor = Next;
      LineEnd = hash ? hash : lineEnd;
      Next = eol ? eol + 1 : End;
      for (const char* c = Cursor; c < LineEnd; ++c)
        if (!IsSeparator(*c))
          return true;
    }
    return false;
  }

  // The next token of the line: false at the line's end.
  bool Token(const char*& first, const char*& last)
  {
    while (Cursor < LineEnd && IsSeparator(*Cursor))
      ++Cursor;
    first = Cursor;
    while (Cursor < LineEnd && !IsSeparator(*Cursor))
      ++Cursor;
    last = Cursor;
    return first < last;
  }

  // A decimal number as istream extraction reads it: [+-]digits[.digits][(e|E)[+-]digits]
  // (digits on at least one side of the point), correctly rounded like the strtod of
  // libstdc++'s num_get; false for any other token and on overflow or underflow (left to the
  // line parser, which knows what the stream does with them).
  bool Double(double& value)
  {
    const char *first, *last;
    if (!Token(first, last) || last - first > 63)
      return false;
    const char* c = first;
    if (*c == '+' || *c == '-')
      ++c;
    int digits = 0;
    while (c < last && *c >= '0' && *c <= '9')
      ++c, ++digits;
    if (c < last && *c == '.')
      for (++c; c < last && *c >= '0' && *c <= '9'; ++c)
        ++digits;
    if (digits == 0)
      return false;
    if (c < last && (*c == 'e' || *c == 'E'))
    {
      ++c;
      if (c < last && (*c == '+' || *c == '-'))
        ++c;
      const char* exponent = c;
      while (c < last && *c >= '0' && *c <= '9')
        ++c;
      if (c == exponent)
        return false;
    }
    if (c != last)
      return false;
    // Correctly rounded, as strtod: the same double (from_chars takes no '+').
    const auto parsed = std::from_chars(*first == '+' ? first + 1 : first, last, value);
    return parsed.ec == std::errc() && parsed.ptr == last && std::isfinite(value) &&
      (value != 0 || IsZero(first, last));
  }

  // [+-]digits, at most 18 digits (exact in a long long).
  bool Integer(long long& value)
  {
    const char *first, *last;
    if (!Token(first, last))
      return false;
    const char* c = first;
    const bool negative = *c == '-';
    if (*c == '+' || *c == '-')
      ++c;
    if (c == last || last - c > 18)
      return false;
    long long v = 0;
    for (; c < last; ++c)
    {
      if (*c < '0' || *c > '9')
        return false;
      v = 10 * v + (*c - '0');
    }
    value = negative ? -v : v;
    return true;
  }

private:
  static bool IsSeparator(char c) { return c == ' ' || c == '\t' || c == '\r'; }
  // Whether a number's digits are all 0 (a 0 that is not an underflow).
  static bool IsZero(const char* first, const char* last)
  {
    for (const char* c = first; c < last && *c != 'e' && *c != 'E'; ++c)
      if (*c >= '1' && *c <= '9')
        return false;
    return true;
  }

  const char* Next;
  const char* End;
  const char* Cursor = nullptr;
  const char* LineEnd = nullptr;
};
} // namespace

bool ReadOffFast(const std::string& text, SurfaceData& surface)
{
  OffText off(text);
  const char *first, *last;
  if (!off.NextLine() || !off.Token(first, last) ||
    std::string(first, last).find("OFF") == std::string::npos)
    return false;
  long long pointCount = 0, faceCount = 0;
  // The counts follow the keyword on its line, or start the next line.
  if (!off.Integer(pointCount))
  {
    if (off.Token(first, last) || !off.NextLine() || !off.Integer(pointCount))
      return false;
  }
  if (!off.Integer(faceCount) || pointCount < 0 || faceCount < 0)
    return false;
  surface = SurfaceData();
  constexpr long long kReserveLimit = 1 << 24;
  surface.points.reserve(3 * static_cast<std::size_t>(std::min(pointCount, kReserveLimit)));
  for (long long i = 0; i < pointCount; ++i)
  {
    double x[3];
    if (!off.NextLine() || !off.Double(x[0]) || !off.Double(x[1]) || !off.Double(x[2]))
      return false;
    surface.points.insert(surface.points.end(), x, x + 3);
  }
  surface.polygonOffsets.reserve(static_cast<std::size_t>(std::min(faceCount, kReserveLimit)) + 1);
  surface.polygonOffsets.push_back(0);
  surface.polygonPoints.reserve(3 * static_cast<std::size_t>(std::min(faceCount, kReserveLimit)));
  for (long long f = 0; f < faceCount; ++f)
  {
    long long n = 0;
    if (!off.NextLine() || !off.Integer(n) || n < 3)
      return false;
    for (long long k = 0; k < n; ++k)
    {
      long long id = 0;
      if (!off.Integer(id) || id < 0 || id >= pointCount)
        return false;
      surface.polygonPoints.push_back(id);
    }
    surface.polygonOffsets.push_back(static_cast<std::int64_t>(surface.polygonPoints.size()));
  }
  return true;
}

SurfaceData ReadOff(const std::string& path)
{
  // The fast parser on the whole text; the line parser for what it declines (and for the
  // message naming the line of a defect). bunny00.off (35k points, 70k faces): 40 -> 10 ms.
  std::string text;
  SurfaceData surface;
  if (ReadWholeFile(path, text) && ReadOffFast(text, surface))
    return surface;
  return ReadOffByLines(path);
}

SurfaceData ReadOffByLines(const std::string& path)
{
  TokenFile file(path);
  std::istringstream line;
  std::string header;
  if (!file.NextLine(line) || !(line >> header) || header.find("OFF") == std::string::npos)
  {
    file.Fail("not an OFF file (expected the keyword OFF)");
  }
  long pointCount = 0, faceCount = 0;
  // The counts may follow OFF on the same line.
  if (!(line >> pointCount >> faceCount))
  {
    if (!file.NextLine(line) || !(line >> pointCount >> faceCount))
    {
      file.Fail("expected 'pointCount faceCount edgeCount'");
    }
  }
  if (pointCount < 0 || faceCount < 0)
  {
    file.Fail("negative counts");
  }
  SurfaceData surface;
  // Reserved up to a bound: the counts of a corrupt header must give its error, not bad_alloc.
  constexpr long kReserveLimit = 1 << 24;
  surface.points.reserve(3 * static_cast<std::size_t>(std::min(pointCount, kReserveLimit)));
  for (long i = 0; i < pointCount; ++i)
  {
    double x[3];
    if (!file.NextLine(line) || !(line >> x[0] >> x[1] >> x[2]))
    {
      file.Fail("expected point " + std::to_string(i) + " as 'x y z'");
    }
    surface.points.insert(surface.points.end(), x, x + 3);
  }
  surface.polygonOffsets.reserve(static_cast<std::size_t>(std::min(faceCount, kReserveLimit)) + 1);
  surface.polygonOffsets.push_back(0);
  surface.polygonPoints.reserve(3 * static_cast<std::size_t>(std::min(faceCount, kReserveLimit)));
  for (long f = 0; f < faceCount; ++f)
  {
    long n;
    if (!file.NextLine(line) || !(line >> n) || n < 3)
    {
      file.Fail("expected face " + std::to_string(f) + " as 'n v0 ... v(n-1)' with n >= 3");
    }
    for (long k = 0; k < n; ++k)
    {
      long long id;
      if (!(line >> id) || id < 0 || id >= pointCount)
      {
        file.Fail("face " + std::to_string(f) + " has a missing or out-of-range point index");
      }
      surface.polygonPoints.push_back(id);
    }
    surface.polygonOffsets.push_back(static_cast<std::int64_t>(surface.polygonPoints.size()));
  }
  return surface;
}

// --- VTK XML .vtp ------------------------------------------------------------------------
namespace
{

// A start tag: its name, attributes, and where its content begins in the file's text.
struct Tag
{
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  bool closing = false;     // </name>
  bool selfClosing = false; // <name ... />
  std::size_t contentStart = 0;

  const std::string* Attribute(const char* key) const
  {
    for (const auto& [k, v] : attributes)
      if (k == key)
        return &v;
    return nullptr;
  }
};

// Reads the tag at text[pos] == '<'; false when it is not well formed. Skips <?...?> and
// comments by returning a tag with an empty name.
bool ParseTag(const std::string& text, std::size_t& pos, Tag& tag)
{
  tag = Tag();
  const std::pair<const char*, const char*> skipped[] = { { "<!--", "-->" }, { "<?", "?>" } };
  for (const auto& [open, close] : skipped)
  {
    if (text.compare(pos, std::strlen(open), open) == 0)
    {
      const std::size_t end = text.find(close, pos);
      if (end == std::string::npos)
        return false;
      pos = end + std::strlen(close);
      return true;
    }
  }
  std::size_t i = pos + 1;
  if (i < text.size() && text[i] == '/')
  {
    tag.closing = true;
    ++i;
  }
  auto isNameChar = [](char c)
  {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '-' ||
      c == '.';
  };
  const std::size_t nameStart = i;
  while (i < text.size() && isNameChar(text[i]))
    ++i;
  tag.name = text.substr(nameStart, i - nameStart);
  if (tag.name.empty())
    return false;
  while (true)
  {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
      ++i;
    if (i >= text.size())
      return false;
    if (text[i] == '>')
    {
      ++i;
      break;
    }
    if (text[i] == '/' && i + 1 < text.size() && text[i + 1] == '>')
    {
      tag.selfClosing = true;
      i += 2;
      break;
    }
    const std::size_t keyStart = i;
    while (i < text.size() && isNameChar(text[i]))
      ++i;
    if (i == keyStart)
      return false;
    std::string key = text.substr(keyStart, i - keyStart);
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
      ++i;
    if (i >= text.size() || text[i] != '=')
      return false;
    ++i;
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
      ++i;
    if (i >= text.size() || (text[i] != '"' && text[i] != '\''))
      return false;
    const char quote = text[i++];
    const std::size_t end = text.find(quote, i);
    if (end == std::string::npos)
      return false;
    std::string value = text.substr(i, end - i);
    // VTK writes names with &amp; &lt; &gt; &quot; &apos; escapes; other entities: decline.
    if (value.find('&') != std::string::npos)
    {
      static const std::pair<const char*, char> entities[] = {
        { "&amp;", '&' }, { "&lt;", '<' }, { "&gt;", '>' }, { "&quot;", '"' }, { "&apos;", '\'' }
      };
      std::string plain;
      for (std::size_t k = 0; k < value.size();)
      {
        bool matched = value[k] != '&';
        if (!matched)
        {
          for (const auto& [entity, c] : entities)
          {
            if (value.compare(k, std::strlen(entity), entity) == 0)
            {
              plain += c;
              k += std::strlen(entity);
              matched = true;
              break;
            }
          }
          if (!matched)
            return false;
          continue;
        }
        plain += value[k++];
      }
      value = plain;
    }
    tag.attributes.emplace_back(std::move(key), std::move(value));
    i = end + 1;
  }
  tag.contentStart = i;
  pos = i;
  return true;
}

template<typename T>
T Load(const unsigned char* bytes)
{
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

// A type of stored values: its name in the file, its size, and how to read one value
// (little-endian) as double or as a 64-bit integer.
struct Scalar
{
  const char* name;
  std::size_t size;
  double (*asDouble)(const unsigned char*);
  std::int64_t (*asInteger)(const unsigned char*);
  bool real;
};

template<typename T>
constexpr Scalar Describe(const char* name)
{
  return { name,
    sizeof(T),
    [](const unsigned char* bytes) { return static_cast<double>(Load<T>(bytes)); },
    [](const unsigned char* bytes) { return static_cast<std::int64_t>(Load<T>(bytes)); },
    std::is_floating_point<T>::value };
}

const Scalar kScalars[] = { Describe<std::int8_t>("Int8"),
  Describe<std::uint8_t>("UInt8"),
  Describe<std::int16_t>("Int16"),
  Describe<std::uint16_t>("UInt16"),
  Describe<std::int32_t>("Int32"),
  Describe<std::uint32_t>("UInt32"),
  Describe<std::int64_t>("Int64"),
  Describe<std::uint64_t>("UInt64"),
  Describe<float>("Float32"),
  Describe<double>("Float64") };

// The type named `type`, or null.
const Scalar* ScalarOf(const std::string& type)
{
  for (const Scalar& scalar : kScalars)
    if (type == scalar.name)
      return &scalar;
  return nullptr;
}

void Convert(const Scalar& type, const unsigned char* bytes, double& value)
{
  value = type.asDouble(bytes);
}
void Convert(const Scalar& type, const unsigned char* bytes, std::int64_t& value)
{
  value = type.asInteger(bytes);
}

int Base64Value(char c)
{
  if (c >= 'A' && c <= 'Z')
    return c - 'A';
  if (c >= 'a' && c <= 'z')
    return c - 'a' + 26;
  if (c >= '0' && c <= '9')
    return c - '0' + 52;
  if (c == '+')
    return 62;
  if (c == '/')
    return 63;
  return -1;
}

// Decodes base64 text from `pos` (whitespace skipped) until `bytes` bytes are out, in whole
// 4-character groups as VTK encodes each part; advances `pos`. False on bad input.
bool DecodeBase64(const char* text,
  std::size_t size,
  std::size_t& pos,
  std::size_t bytes,
  std::vector<unsigned char>& out)
{
  out.clear();
  out.reserve(bytes + 2);
  while (out.size() < bytes)
  {
    int group[4];
    int n = 0;
    while (n < 4)
    {
      if (pos >= size)
        return false;
      const char c = text[pos++];
      if (std::isspace(static_cast<unsigned char>(c)))
        continue;
      group[n++] = c == '=' ? -2 : Base64Value(c);
      if (group[n - 1] == -1)
        return false;
    }
    if (group[0] < 0 || group[1] < 0)
      return false;
    out.push_back(static_cast<unsigned char>((group[0] << 2) | (group[1] >> 4)));
    if (group[2] >= 0)
      out.push_back(static_cast<unsigned char>(((group[1] & 15) << 4) | (group[2] >> 2)));
    if (group[2] >= 0 && group[3] >= 0)
      out.push_back(static_cast<unsigned char>(((group[2] & 3) << 6) | group[3]));
    if (group[2] < 0 || group[3] < 0)
      break; // padding ends this part
  }
  if (out.size() < bytes)
    return false;
  out.resize(bytes);
  return true;
}

// The binary parts of a VTK XML file: how the arrays are stored.
struct Encoding
{
  std::size_t headerSize = 4; // UInt32 or UInt64 block headers
  bool zlib = false;
  const std::string* text = nullptr; // the whole file
  std::size_t appendedStart = 0;     // after the '_' of <AppendedData>
  bool appendedBase64 = false;
};

std::uint64_t HeaderWord(const unsigned char* bytes, std::size_t size)
{
  return size == 8 ? Load<std::uint64_t>(bytes) : Load<std::uint32_t>(bytes);
}

// Reads the raw bytes of one binary array (header, optional zlib blocks) from `text` at
// `pos`, base64-encoded or not. False when malformed.
bool ReadBinary(const Encoding& encoding,
  const char* text,
  std::size_t size,
  std::size_t pos,
  bool base64,
  std::size_t expectedBytes,
  std::vector<unsigned char>& out)
{
  const std::size_t w = encoding.headerSize;
  std::vector<unsigned char> scratch;
  // Takes `bytes` bytes at pos: decoded when base64 (a part of its own), raw otherwise.
  auto take = [&](std::size_t bytes, std::vector<unsigned char>& into)
  {
    if (base64)
      return DecodeBase64(text, size, pos, bytes, into);
    if (pos + bytes > size)
      return false;
    into.assign(text + pos, text + pos + bytes);
    pos += bytes;
    return true;
  };
  if (!encoding.zlib)
  {
    // One part: the byte count, then the data.
    if (base64)
    {
      std::vector<unsigned char> all;
      std::size_t start = pos;
      if (!DecodeBase64(text, size, start, w, all))
        return false;
      const std::uint64_t count = HeaderWord(all.data(), w);
      if (count != expectedBytes)
        return false;
      if (!DecodeBase64(text, size, pos, w + count, all))
        return false;
      out.assign(all.begin() + static_cast<std::ptrdiff_t>(w), all.end());
      return true;
    }
    if (!take(w, scratch) || HeaderWord(scratch.data(), w) != expectedBytes)
      return false;
    return take(expectedBytes, out);
  }
  // zlib: [blocks, blockSize, lastBlockSize, compressed size of each block], then the blocks.
  std::vector<unsigned char> header;
  std::size_t headerPos = pos;
  if (base64)
  {
    if (!DecodeBase64(text, size, headerPos, 3 * w, header))
      return false;
  }
  else if (pos + 3 * w > size)
    return false;
  else
    header.assign(text + pos, text + pos + 3 * w);
  const std::uint64_t blocks = HeaderWord(header.data(), w);
  const std::uint64_t blockSize = HeaderWord(header.data() + w, w);
  const std::uint64_t lastSize = HeaderWord(header.data() + 2 * w, w);
  if (blocks > size || (blocks > 0 && blockSize == 0))
    return false;
  if (!take((3 + blocks) * w, header))
    return false;
  const std::uint64_t total =
    blocks == 0 ? 0 : (blocks - 1) * blockSize + (lastSize ? lastSize : blockSize);
  if (total != expectedBytes)
    return false;
  std::uint64_t compressedTotal = 0;
  for (std::uint64_t b = 0; b < blocks; ++b)
    compressedTotal += HeaderWord(header.data() + (3 + b) * w, w);
  if (compressedTotal > size || !take(compressedTotal, scratch))
    return false;
  // zlib expands by at most 1032:1: a larger claim is a corrupt header, not memory to take.
  if (expectedBytes / 1032 > compressedTotal + blocks)
    return false;
  out.resize(expectedBytes);
  std::size_t in = 0, at = 0;
  for (std::uint64_t b = 0; b < blocks; ++b)
  {
    const std::uint64_t compressed = HeaderWord(header.data() + (3 + b) * w, w);
    const std::uint64_t expected = b + 1 == blocks && lastSize ? lastSize : blockSize;
    uLongf produced = static_cast<uLongf>(expected);
    if (uncompress(
          out.data() + at, &produced, scratch.data() + in, static_cast<uLong>(compressed)) !=
        Z_OK ||
      produced != expected)
      return false;
    in += compressed;
    at += expected;
  }
  return true;
}

// One DataArray: its values as doubles (or 64-bit integers), whatever its storage.
struct ArrayRef
{
  Tag tag;
  const Scalar* type = nullptr;
  int components = 1;
};

template<typename Out>
bool ReadArray(const Encoding& encoding,
  const ArrayRef& array,
  std::size_t tuples,
  std::vector<Out>& values)
{
  const std::size_t count = tuples * static_cast<std::size_t>(array.components);
  const std::string* format = array.tag.Attribute("format");
  const std::string& text = *encoding.text;
  // Every value takes at least a byte of the file, or 1/1032 of one compressed: a larger
  // count is a corrupt header (left to VTK), not memory to take.
  if (tuples > text.size() * 1032 || count / 1032 > text.size())
    return false;
  values.resize(count);
  if (!format || *format == "ascii")
  {
    if (!format)
      return false;
    // Numbers separated by white space until the next tag.
    const char* c = text.c_str() + array.tag.contentStart;
    const bool real = array.type->real;
    const bool single = array.type->size == 4;
    for (std::size_t i = 0; i < count; ++i)
    {
      char* end = nullptr;
      if (real)
      {
        const double x = single ? std::strtof(c, &end) : std::strtod(c, &end);
        values[i] = static_cast<Out>(x);
      }
      else
        values[i] = static_cast<Out>(std::strtoll(c, &end, 10));
      if (end == c)
        return false;
      c = end;
    }
    return true;
  }
  std::vector<unsigned char> bytes;
  const std::size_t expected = count * array.type->size;
  if (*format == "binary")
  {
    if (!ReadBinary(
          encoding, text.c_str(), text.size(), array.tag.contentStart, true, expected, bytes))
      return false;
  }
  else if (*format == "appended")
  {
    const std::string* offset = array.tag.Attribute("offset");
    if (!offset || encoding.appendedStart == 0)
      return false;
    char* end = nullptr;
    const unsigned long long at = std::strtoull(offset->c_str(), &end, 10);
    if (end == offset->c_str() || encoding.appendedStart + at > text.size())
      return false;
    if (!ReadBinary(encoding,
          text.c_str(),
          text.size(),
          encoding.appendedStart + at,
          encoding.appendedBase64,
          expected,
          bytes))
      return false;
  }
  else
    return false;
  for (std::size_t i = 0; i < count; ++i)
    Convert(*array.type, bytes.data() + i * array.type->size, values[i]);
  return true;
}

bool ParseCount(const Tag& tag, const char* key, std::int64_t& value)
{
  const std::string* text = tag.Attribute(key);
  if (!text)
  {
    value = 0;
    return true;
  }
  char* end = nullptr;
  value = std::strtoll(text->c_str(), &end, 10);
  return end != text->c_str() && *end == '\0' && value >= 0;
}
} // namespace

bool ReadVtp(const std::string& path, SurfaceData& surface)
{
  std::string text;
  if (!ReadWholeFile(path, text))
    return false;
  Encoding encoding;
  encoding.text = &text;
  // The XML part ends where the appended data begin; raw data may hold any byte.
  std::size_t xmlEnd = text.size();
  const std::size_t appended = text.find("<AppendedData");
  if (appended != std::string::npos)
  {
    std::size_t pos = appended;
    Tag tag;
    if (!ParseTag(text, pos, tag))
      return false;
    const std::string* how = tag.Attribute("encoding");
    if (!how || (*how != "raw" && *how != "base64"))
      return false;
    encoding.appendedBase64 = *how == "base64";
    const std::size_t underscore = text.find('_', pos);
    if (underscore == std::string::npos)
      return false;
    encoding.appendedStart = underscore + 1;
    xmlEnd = appended;
  }

  std::vector<std::string> open; // the element path
  Tag piece;
  int pieces = 0;
  ArrayRef points, vertsOffsets, linesOffsets, stripsOffsets, polysConnectivity, polysOffsets;
  std::vector<ArrayRef> pointArrays;
  bool sawFile = false;
  for (std::size_t pos = text.find('<'); pos < xmlEnd; pos = text.find('<', pos))
  {
    Tag tag;
    if (!ParseTag(text, pos, tag))
      return false;
    if (tag.name.empty())
      continue;
    if (tag.closing)
    {
      if (open.empty() || open.back() != tag.name)
        return false;
      open.pop_back();
      continue;
    }
    if (tag.name == "VTKFile")
    {
      const std::string* type = tag.Attribute("type");
      const std::string* order = tag.Attribute("byte_order");
      const std::string* header = tag.Attribute("header_type");
      const std::string* compressor = tag.Attribute("compressor");
      const std::string* version = tag.Attribute("version");
      // Version 2 and later store cell offsets with a leading 0: left to VTK.
      if (!type || *type != "PolyData" || !order || *order != "LittleEndian" || !version ||
        std::strtod(version->c_str(), nullptr) >= 2.0)
        return false;
      if (header && *header != "UInt32" && *header != "UInt64")
        return false;
      encoding.headerSize = header && *header == "UInt64" ? 8 : 4;
      if (compressor && !compressor->empty())
      {
        if (*compressor != "vtkZLibDataCompressor")
          return false;
        encoding.zlib = true;
      }
      sawFile = true;
    }
    else if (tag.name == "Piece")
    {
      piece = tag;
      ++pieces;
    }
    else if (tag.name == "DataArray" && open.size() >= 2)
    {
      ArrayRef array;
      array.tag = tag;
      const std::string* type = tag.Attribute("type");
      array.type = type ? ScalarOf(*type) : nullptr;
      if (const std::string* components = tag.Attribute("NumberOfComponents"))
        array.components = std::atoi(components->c_str());
      const std::string& section = open.back();
      const std::string* name = tag.Attribute("Name");
      if (section == "PointData")
      {
        if (array.type && array.components >= 1 && name)
          pointArrays.push_back(array);
      }
      else if (!array.type || array.components < 1)
      {
        if (section != "CellData" && section != "FieldData")
          return false;
      }
      else if (section == "Points")
        points = array;
      else if (name && *name == "offsets" && section == "Verts")
        vertsOffsets = array;
      else if (name && *name == "offsets" && section == "Lines")
        linesOffsets = array;
      else if (name && *name == "offsets" && section == "Strips")
        stripsOffsets = array;
      else if (name && *name == "connectivity" && section == "Polys")
        polysConnectivity = array;
      else if (name && *name == "offsets" && section == "Polys")
        polysOffsets = array;
    }
    if (!tag.selfClosing)
      open.push_back(tag.name);
  }
  if (!sawFile || pieces != 1)
    return false;
  std::int64_t pointCount = 0, polyCount = 0;
  if (!ParseCount(piece, "NumberOfPoints", pointCount) ||
    !ParseCount(piece, "NumberOfVerts", surface.vertexCells) ||
    !ParseCount(piece, "NumberOfLines", surface.lineCells) ||
    !ParseCount(piece, "NumberOfStrips", surface.stripCells) ||
    !ParseCount(piece, "NumberOfPolys", polyCount))
    return false;
  if (pointCount == 0 || !points.type || points.components != 3 ||
    !ReadArray(encoding, points, static_cast<std::size_t>(pointCount), surface.points))
    return false;
  // The vertex, line and strip cells only shift the input cell ids of the polygons.
  std::vector<std::int64_t> ends;
  for (const auto& [count, offsets] : { std::make_pair(surface.vertexCells, &vertsOffsets),
         std::make_pair(surface.lineCells, &linesOffsets),
         std::make_pair(surface.stripCells, &stripsOffsets) })
  {
    if (count > 0 &&
      (!offsets->type || offsets->components != 1 ||
        !ReadArray(encoding, *offsets, static_cast<std::size_t>(count), ends)))
      return false;
  }
  surface.polygonOffsets.assign(1, 0);
  surface.polygonPoints.clear();
  if (polyCount > 0)
  {
    if (!polysOffsets.type || !polysConnectivity.type || polysOffsets.components != 1 ||
      polysConnectivity.components != 1 ||
      !ReadArray(encoding, polysOffsets, static_cast<std::size_t>(polyCount), ends))
      return false;
    // Offsets are the ends of the cells (files before version 2): increasing, the last one
    // the length of the connectivity.
    std::int64_t previous = 0;
    for (std::int64_t end : ends)
    {
      if (end < previous)
        return false;
      previous = end;
    }
    if (!ReadArray(
          encoding, polysConnectivity, static_cast<std::size_t>(previous), surface.polygonPoints))
      return false;
    surface.polygonOffsets.insert(surface.polygonOffsets.end(), ends.begin(), ends.end());
  }
  for (const ArrayRef& array : pointArrays)
  {
    PointArray values;
    values.name = *array.tag.Attribute("Name");
    values.components = array.components;
    if (!ReadArray(encoding, array, static_cast<std::size_t>(pointCount), values.values))
      return false;
    surface.pointArrays.push_back(std::move(values));
  }
  return true;
}

// --- VTK XML .vtu ------------------------------------------------------------------------
namespace
{

// One appended array of the file: its XML attributes; `stored`, written first (the whole
// block when compressed, else its byte count); then `raw`, the uncompressed values straight
// from the caller's vector, not copied: they are most of the file (20 MB for fandisk at
// h = 0.0207).
struct OutArray
{
  std::string attributes; // type, Name, NumberOfComponents... without format/offset
  std::vector<unsigned char> stored;
  const void* raw = nullptr;
  std::size_t rawBytes = 0;
  bool narrowed = false; // raw holds Int64 values written as Int32 (rawBytes: the Int32 bytes)
  std::size_t size() const { return stored.size() + rawBytes; }
};

template<typename T>
void Append(std::vector<unsigned char>& out, const T& value)
{
  const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

// The block as vtkXMLWriter stores it with zlib: [blocks, block size, last block size,
// compressed sizes] then the compressed blocks.
std::vector<unsigned char> Compress(const void* data, std::size_t bytes)
{
  std::vector<unsigned char> out;
  const auto* in = static_cast<const unsigned char*>(data);
  constexpr std::size_t kBlockSize = 32768; // vtkXMLWriter's
  constexpr int kLevel = 5;                 // vtkXMLWriter's CompressionLevel
  const std::size_t blocks = (bytes + kBlockSize - 1) / kBlockSize;
  const std::size_t last = bytes % kBlockSize;
  std::vector<unsigned char> body;
  std::vector<std::uint64_t> sizes;
  std::vector<unsigned char> buffer(compressBound(kBlockSize));
  for (std::size_t b = 0; b < blocks; ++b)
  {
    const std::size_t size = b + 1 == blocks && last ? last : kBlockSize;
    uLongf produced = static_cast<uLongf>(buffer.size());
    compress2(buffer.data(), &produced, in + b * kBlockSize, static_cast<uLong>(size), kLevel);
    body.insert(body.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(produced));
    sizes.push_back(produced);
  }
  Append(out, static_cast<std::uint64_t>(blocks));
  Append(out, static_cast<std::uint64_t>(kBlockSize));
  Append(out, static_cast<std::uint64_t>(last));
  for (std::uint64_t size : sizes)
    Append(out, size);
  out.insert(out.end(), body.begin(), body.end());
  return out;
}

// Uncompressed, as vtkXMLWriter stores it: a UInt64 byte count then the values, which are
// written from `values` itself: it must outlive the writing (hence no temporaries).
template<typename T>
OutArray MakeArray(const std::string& attributes, const std::vector<T>& values, bool compress)
{
  const std::size_t bytes = values.size() * sizeof(T);
  if (compress)
    return { attributes, Compress(values.data(), bytes), nullptr, 0 };
  OutArray array{
    attributes, std::vector<unsigned char>(sizeof(std::uint64_t)), values.data(), bytes
  };
  const std::uint64_t count = bytes;
  std::memcpy(array.stored.data(), &count, sizeof count);
  return array;
}
template<typename T>
OutArray MakeArray(const std::string& attributes, const std::vector<T>&& values, bool) = delete;

// A cell array (connectivity, offsets): Int32 when `narrow` (every value fits), as VTK writes
// a vtkCellArray of 32-bit storage; a reader gives such a vtkCellArray back. Uncompressed,
// the values are narrowed as they are written (no copy of the array).
OutArray MakeIdArray(const std::string& attributes,
  const std::vector<std::int64_t>& values,
  bool narrow,
  bool compress)
{
  if (!narrow)
    return MakeArray("type=\"Int64\" " + attributes, values, compress);
  if (compress)
  {
    const std::vector<std::int32_t> narrowed(values.begin(), values.end());
    return { "type=\"Int32\" " + attributes,
      Compress(narrowed.data(), narrowed.size() * sizeof(std::int32_t)),
      nullptr,
      0 };
  }
  const std::uint64_t bytes = values.size() * sizeof(std::int32_t);
  OutArray array{ "type=\"Int32\" " + attributes,
    std::vector<unsigned char>(sizeof(std::uint64_t)),
    values.data(),
    bytes,
    true };
  std::memcpy(array.stored.data(), &bytes, sizeof bytes);
  return array;
}
OutArray MakeIdArray(const std::string&, const std::vector<std::int64_t>&&, bool, bool) = delete;

// Point ids and the cells' offsets below 2^31.
bool CellIdsFitInt32(const SurfaceMeshOutput& mesh)
{
  constexpr std::int64_t kMax = std::numeric_limits<std::int32_t>::max();
  return static_cast<std::int64_t>(mesh.mesh.points.size() / 3) <= kMax &&
    static_cast<std::int64_t>(mesh.cells.size()) <= kMax;
}
} // namespace

void WriteVtu(const SurfaceMeshOutput& mesh, const std::string& path, bool compress)
{
  // Arrays in the order and with the types of vtkTetMesher's output as VTK writes it.
  std::vector<OutArray> fields, pointData, cellData;
  std::vector<std::vector<double>> fieldValues;
  fieldValues.reserve(mesh.fieldData.size());
  for (const auto& [name, value] : mesh.fieldData)
  {
    fieldValues.push_back({ value });
    fields.push_back(MakeArray(
      "type=\"Float64\" Name=\"" + name + "\" NumberOfTuples=\"1\"", fieldValues.back(), compress));
  }
  if (!mesh.mesh.vertexSize.empty())
    pointData.push_back(MakeArray("type=\"Float64\" Name=\"h\"", mesh.mesh.vertexSize, compress));
  cellData.push_back(MakeArray("type=\"Int32\" Name=\"RegionId\"", mesh.mesh.regionIds, compress));
  if (!mesh.regionAttribute.empty())
    cellData.push_back(
      MakeArray("type=\"Float64\" Name=\"RegionAttribute\"", mesh.regionAttribute, compress));
  cellData.push_back(
    MakeArray("type=\"Int64\" IdType=\"1\" Name=\"InputFaceIds\" NumberOfComponents=\"4\"",
      mesh.inputFaceIds,
      compress));
  cellData.push_back(
    MakeArray("type=\"Float64\" Name=\"Quality\"", mesh.quality.quality, compress));
  cellData.push_back(
    MakeArray("type=\"Float64\" Name=\"MinDihedralAngle\"", mesh.quality.minDihedral, compress));
  cellData.push_back(
    MakeArray("type=\"Float64\" Name=\"MaxDihedralAngle\"", mesh.quality.maxDihedral, compress));
  const std::size_t tetCount = mesh.cells.size() / 4;
  std::vector<OutArray> pointsArray, cells;
  pointsArray.push_back(MakeArray(
    "type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"", mesh.mesh.points, compress));
  // Offsets are the ends of the cells, as VTK 9.1 writes them (file version 1.0).
  std::vector<std::int64_t> ends(tetCount);
  for (std::size_t t = 0; t < tetCount; ++t)
    ends[t] = static_cast<std::int64_t>(4 * (t + 1));
  // The cells' ids as Int32 where they fit, as the VTK path writes them (WriteVolumeMesh):
  // fandisk at h = 0.0103, 1.1M tets, is 98 MB instead of 121. (InputFaceIds stays Int64:
  // VTK reads an Int32 one back as a vtkIntArray, not a vtkIdTypeArray.)
  const bool narrow = CellIdsFitInt32(mesh);
  cells.push_back(MakeIdArray("Name=\"connectivity\"", mesh.cells, narrow, compress));
  cells.push_back(MakeIdArray("Name=\"offsets\"", ends, narrow, compress));
  const std::vector<std::uint8_t> types(tetCount, 10 /* VTK_TETRA */);
  cells.push_back(MakeArray("type=\"UInt8\" Name=\"types\"", types, compress));

  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                    "byte_order=\"LittleEndian\" header_type=\"UInt64\"";
  if (compress)
    xml += " compressor=\"vtkZLibDataCompressor\"";
  xml += ">\n  <UnstructuredGrid>\n";
  std::uint64_t offset = 0;
  auto section =
    [&xml, &offset](
      const char* open, const char* close, const std::vector<OutArray>& arrays, const char* indent)
  {
    xml += open;
    for (const OutArray& array : arrays)
    {
      xml += indent;
      xml += "<DataArray " + array.attributes + " format=\"appended\" offset=\"" +
        std::to_string(offset) + "\"/>\n";
      offset += array.size();
    }
    xml += close;
  };
  section("    <FieldData>\n", "    </FieldData>\n", fields, "      ");
  xml += "    <Piece NumberOfPoints=\"" + std::to_string(mesh.mesh.points.size() / 3) +
    "\" NumberOfCells=\"" + std::to_string(tetCount) + "\">\n";
  section("      <PointData>\n", "      </PointData>\n", pointData, "        ");
  section("      <CellData Scalars=\"Quality\">\n", "      </CellData>\n", cellData, "        ");
  section("      <Points>\n", "      </Points>\n", pointsArray, "        ");
  section("      <Cells>\n", "      </Cells>\n", cells, "        ");
  xml += "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";

  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), std::fclose);
  bool ok = file != nullptr;
  auto write = [&](const void* data, std::size_t size)
  { ok = ok && std::fwrite(data, 1, size, file.get()) == size; };
  write(xml.data(), xml.size());
  for (const auto* arrays : { &fields, &pointData, &cellData, &pointsArray, &cells })
    for (const OutArray& array : *arrays)
    {
      write(array.stored.data(), array.stored.size());
      if (array.narrowed)
      {
        const auto* values = static_cast<const std::int64_t*>(array.raw);
        const std::size_t count = array.rawBytes / sizeof(std::int32_t);
        std::vector<std::int32_t> chunk;
        constexpr std::size_t kChunk = 1 << 16;
        for (std::size_t first = 0; first < count; first += kChunk)
        {
          chunk.assign(values + first, values + std::min(count, first + kChunk));
          write(chunk.data(), chunk.size() * sizeof(std::int32_t));
        }
      }
      else if (array.rawBytes > 0)
        write(array.raw, array.rawBytes);
    }
  const char tail[] = "\n  </AppendedData>\n</VTKFile>\n";
  write(tail, sizeof tail - 1);
  ok = ok && std::fflush(file.get()) == 0;
  if (!ok)
  {
    Fail(path, "could not be written");
  }
}

} // namespace cli
} // namespace tetmesher
