// Base64 (RFC 4648 §4, standard alphabet with '=' padding) for the data: URIs of the report's
// embedded pictures. Decoding is the inverse the tests check the page with.
#pragma once
#include <string>
#include <string_view>

namespace sgnlf::report {

std::string base64_encode(std::string_view bytes);
// Throws sgnlf::Error on a character outside the alphabet, bad padding or a length that is not
// a multiple of 4.
std::string base64_decode(std::string_view text);

}  // namespace sgnlf::report
