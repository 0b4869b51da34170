#!/bin/sh
# Rebuild the studio page's assets (../assets/) from src/ with the locked npm packages.
# Needs Node.js and npm at development time only; the built files ship in the wheel.
set -e
cd "$(dirname "$0")"
npm ci --no-audit --no-fund
npm run build
