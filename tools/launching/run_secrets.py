"""The credentials of one secured run (`teleo launch --secure`, docs/bus.md "Security").

`make_secrets(folder, run, agents, hosts)` writes, in a folder only its owner can enter:

    ca.pem            the run's own certificate authority (its private key is never written:
                      nothing but this run's router can ever be certified by it)
    router.pem/.key   the router's TLS certificate (names: localhost, 127.0.0.1 and `hosts`)
    users.txt         user:password, one line per process of the run (the router's dictionary)
    router.json       the router's security file (bus/security.py RouterSecurity), with the
                      access-control list of the run
    <user>.cred.json  one credentials file per user (user, password, "ca.pem")

Every file is 0600. To run an agent on another host, copy the folder there (scp -rp) and give
it to `teleo launch --join ... --secrets FOLDER`; the files name each other relatively.
"""

from __future__ import annotations

import datetime
import ipaddress
import secrets
import socket
from dataclasses import dataclass
from pathlib import Path

from bus.security import (
    Credentials,
    RouterSecurity,
    access_control,
    process_users,
    write_private,
)

VALID_DAYS = 30


@dataclass(frozen=True)
class RunSecrets:
    """Where the files of a run's secrets are."""

    folder: Path

    @property
    def router(self) -> Path:
        return self.folder / "router.json"

    def credentials(self, user: str) -> Path:
        return self.folder / f"{user}.cred.json"

    def check(self, users: list[str]) -> None:
        """Raise FileNotFoundError naming the first missing file (a folder copied partly)."""
        for path in [self.folder / "ca.pem", *(self.credentials(u) for u in users)]:
            if not path.is_file():
                raise FileNotFoundError(f"{path}: missing from the secrets folder")


def make_secrets(folder: Path, run: str, agents: list[str], hosts: list[str]) -> RunSecrets:
    """Generate a run's CA, router certificate, passwords and ACL into `folder` (0700)."""
    from cryptography.hazmat.primitives import serialization

    folder.mkdir(parents=True, exist_ok=True, mode=0o700)
    folder.chmod(0o700)
    ca_key, ca_cert = _authority(run)
    key, cert = _router_certificate(run, ca_key, ca_cert, hosts)
    pem = serialization.Encoding.PEM
    write_private(folder / "ca.pem", ca_cert.public_bytes(pem).decode())
    write_private(folder / "router.pem", cert.public_bytes(pem).decode())
    write_private(folder / "router.key", key.private_bytes(
        pem, serialization.PrivateFormat.PKCS8, serialization.NoEncryption()).decode())
    users = process_users(agents)
    passwords = {u: secrets.token_urlsafe(24) for u in users}
    write_private(folder / "users.txt", "".join(f"{u}:{p}\n" for u, p in passwords.items()))
    for user, password in passwords.items():
        Credentials(user, password, "ca.pem").save(folder / f"{user}.cred.json")
    RouterSecurity(str(folder / "ca.pem"), str(folder / "router.pem"),
                   str(folder / "router.key"), str(folder / "users.txt"),
                   access_control(run, users)).save(folder / "router.json")
    return RunSecrets(folder)


def _name(common: str):
    from cryptography import x509
    from cryptography.x509.oid import NameOID

    return x509.Name([x509.NameAttribute(NameOID.ORGANIZATION_NAME, "teleo"),
                      x509.NameAttribute(NameOID.COMMON_NAME, common)])


def _validity(builder):
    now = datetime.datetime.now(datetime.UTC)
    return builder.not_valid_before(now - datetime.timedelta(minutes=5)).not_valid_after(
        now + datetime.timedelta(days=VALID_DAYS))


def _authority(run: str):
    from cryptography import x509
    from cryptography.hazmat.primitives import hashes
    from cryptography.hazmat.primitives.asymmetric import ec

    key = ec.generate_private_key(ec.SECP256R1())
    name = _name(f"teleo run {run} CA")
    cert = _validity(x509.CertificateBuilder().subject_name(name).issuer_name(name)
                     .public_key(key.public_key()).serial_number(x509.random_serial_number()))
    cert = (cert.add_extension(x509.BasicConstraints(ca=True, path_length=0), critical=True)
            .add_extension(x509.KeyUsage(digital_signature=True, key_cert_sign=True,
                                         crl_sign=True, content_commitment=False,
                                         key_encipherment=False, data_encipherment=False,
                                         key_agreement=False, encipher_only=False,
                                         decipher_only=False), critical=True)
            .sign(key, hashes.SHA256()))
    return key, cert


def _router_certificate(run: str, ca_key, ca_cert, hosts: list[str]):
    from cryptography import x509
    from cryptography.hazmat.primitives import hashes
    from cryptography.hazmat.primitives.asymmetric import ec
    from cryptography.x509.oid import ExtendedKeyUsageOID

    key = ec.generate_private_key(ec.SECP256R1())
    cert = _validity(x509.CertificateBuilder().subject_name(_name(f"teleo run {run} router"))
                     .issuer_name(ca_cert.subject).public_key(key.public_key())
                     .serial_number(x509.random_serial_number()))
    cert = (cert.add_extension(x509.SubjectAlternativeName(_alt_names(hosts)), critical=False)
            .add_extension(x509.BasicConstraints(ca=False, path_length=None), critical=True)
            .add_extension(x509.ExtendedKeyUsage([ExtendedKeyUsageOID.SERVER_AUTH]),
                           critical=False)
            .sign(ca_key, hashes.SHA256()))
    return key, cert


def _alt_names(hosts: list[str]) -> list:
    """localhost, 127.0.0.1, this host's name and the given names or addresses."""
    from cryptography import x509

    names: list = []
    for host in dict.fromkeys(["localhost", "127.0.0.1", socket.gethostname(), *hosts]):
        try:
            names.append(x509.IPAddress(ipaddress.ip_address(host)))
        except ValueError:
            names.append(x509.DNSName(host))
    return names


def host_of(endpoint: str) -> str:
    """The host part of a zenoh endpoint such as tls/10.0.0.1:7447 ("" for a wildcard)."""
    address = endpoint.split("/", 1)[-1].split("#", 1)[0]
    host = address.rsplit(":", 1)[0].strip("[]")
    return "" if host in ("0.0.0.0", "::", "") else host
