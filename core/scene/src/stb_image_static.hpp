#pragma once
// stb_image with its implementation compiled static into the one source that includes this (Debian's
// libstb-dev ships headers only, and ui/'s renderer compiles its own copy: static keeps them apart).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>
