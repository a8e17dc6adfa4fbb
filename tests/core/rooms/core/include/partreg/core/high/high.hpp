#pragma once
// The higher room's public header.
