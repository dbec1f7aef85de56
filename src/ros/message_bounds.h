#pragma once

#include <ros/message_traits.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/status.h"

// roscpp's deserializer resizes a string or vector to the length it reads before it checks
// that the bytes are there, so one corrupt length in a bag makes it allocate gigabytes. The
// layout of a message type lets us check a message's serialized bytes before that happens.
namespace semchain::ros1 {

// The layout of a ROS message type, parsed from its full definition text as
// ros::message_traits::definition<M>() or a bag's connection header gives it: the main type,
// then each nested type after a line of '=' and a line "MSG: pkg/Type".
class MessageLayout {
 public:
  // 'type' is the main type, e.g. "sensor_msgs/LaserScan". An unknown type name, bad array
  // syntax or a type that contains itself is an error.
  static Result<MessageLayout> Parse(const std::string& type, const std::string& definition);

  // Ok when 'bytes' hold exactly one serialized message of this type: every string and array
  // length fits in the bytes that follow it and no byte is left over. Else an error that
  // names the field, e.g. "field ranges: 4294967280 elements of 4 bytes, 12 bytes left".
  // Never allocates in proportion to a length read from 'bytes'.
  Status Check(const std::uint8_t* bytes, std::size_t size) const;

  const std::string& type() const { return types_.front().name; }

 private:
  enum class Kind { kPrimitive, kString, kMessage };
  enum class Array { kNone, kVariable, kFixed };
  struct Field {
    std::string name;
    Kind kind = Kind::kPrimitive;
    std::uint64_t primitive_size = 0;  // kPrimitive
    std::size_t type = 0;              // kMessage: index in types_
    Array array = Array::kNone;
    std::uint64_t fixed_count = 0;  // Array::kFixed
  };
  struct Type {
    std::string name;
    std::vector<Field> fields;
    std::uint64_t min_size = 0;  // saturates at UINT64_MAX
    bool fixed = true;           // every value takes exactly min_size bytes
    int height = 1;              // 1 + the height of its deepest nested type
  };
  // The least size of one element of 'field' (one array element), and whether it is exact.
  struct Size {
    std::uint64_t min = 0;
    bool fixed = true;
  };
  class Reader;

  MessageLayout() = default;
  Size ElementSize(const Field& field) const;
  Status ComputeSizes(std::size_t type, std::vector<int>& state, int depth);
  // These return errors relative to where they are called from (".name: ..." for a type,
  // ": ..." or "[3].name: ..." for a field) so that the caller can put the path in front.
  Status CheckType(std::size_t type, Reader& reader) const;
  Status CheckField(const Field& field, Reader& reader) const;
  Status CheckElement(const Field& field, Reader& reader) const;

  std::vector<Type> types_;  // types_[0] is the main type
};

// The layout of a compiled message type, parsed once.
template <typename M>
const MessageLayout& LayoutOf() {
  static const MessageLayout layout = [] {
    Result<MessageLayout> parsed = MessageLayout::Parse(ros::message_traits::datatype<M>(),
                                                        ros::message_traits::definition<M>());
    // A compiled type's definition comes from genmsg, so failing to parse it is our bug.
    if (!parsed.ok()) std::fprintf(stderr, "%s\n", parsed.status().message().c_str());
    SEMCHAIN_CHECK(parsed.ok());
    return std::move(parsed).value();
  }();
  return layout;
}

}  // namespace semchain::ros1
