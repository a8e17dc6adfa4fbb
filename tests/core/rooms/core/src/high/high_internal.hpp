#pragma once
// The higher room's internal header.
