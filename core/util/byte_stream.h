// Plain binary encoding of numbers and arrays of trivially copyable values, in this machine's
// byte order, for checkpoints a process writes and a later one on the same kind of machine
// reads back bit for bit. The reader checks every length against what remains and against a
// caller's bound, so a truncated or altered file is an error, never a wild read.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace pf {

class ByteWriter {
public:
    template <typename T>
    void Value(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    // The count, then the elements.
    template <typename T>
    void Array(std::span<const T> values) {
        static_assert(std::is_trivially_copyable_v<T>);
        Value<uint64_t>(values.size());
        bytes_.append(reinterpret_cast<const char*>(values.data()), values.size_bytes());
    }
    void String(std::string_view text) { Array(std::span<const char>(text.data(), text.size())); }

    std::string& Bytes() { return bytes_; }

private:
    std::string bytes_;
};

class ByteReader {
public:
    explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}

    // False (and nothing read) when fewer bytes remain than asked for.
    template <typename T>
    bool Value(T* value) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (bytes_.size() < sizeof(T)) return false;
        std::memcpy(value, bytes_.data(), sizeof(T));
        bytes_.remove_prefix(sizeof(T));
        return true;
    }
    // False when the count exceeds `max_count` or what remains.
    template <typename T>
    bool Array(std::vector<T>* values, uint64_t max_count) {
        static_assert(std::is_trivially_copyable_v<T>);
        uint64_t count = 0;
        if (!Value(&count) || count > max_count || count > bytes_.size() / sizeof(T)) return false;
        values->resize(count);
        if (count > 0) std::memcpy(values->data(), bytes_.data(), count * sizeof(T));
        bytes_.remove_prefix(count * sizeof(T));
        return true;
    }
    bool String(std::string* text, uint64_t max_bytes) {
        std::vector<char> chars;
        if (!Array(&chars, max_bytes)) return false;
        text->assign(chars.begin(), chars.end());
        return true;
    }
    // The next `size` bytes, not copied (valid as long as the reader's bytes); false when
    // fewer remain.
    bool Bytes(uint64_t size, std::string_view* bytes) {
        if (size > bytes_.size()) return false;
        *bytes = bytes_.substr(0, size);
        bytes_.remove_prefix(size);
        return true;
    }
    bool AtEnd() const { return bytes_.empty(); }

private:
    std::string_view bytes_;
};

}  // namespace pf
