// The one translation unit that holds stb's implementations (Debian's libstb-dev ships headers only).
// Built without warnings: it is third-party code (see ui/CMakeLists.txt).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>
